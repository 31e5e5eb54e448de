//! Storage of the importance maps: per object, compressed sparse rows — the entries of
//! vertex v are `first[v]..first[v + 1]`, each a light index and n² + 1 values in one
//! flat array (the n² SH coefficients, then the indirect irradiance) — so an entry costs
//! 4 + 4(n² + 1) bytes (4 + 2(n² + 1) with f16 values) and no per-vertex or per-entry
//! allocation (the nested lists this replaces cost about twice that on the heap). f16
//! values are stored relative to the largest magnitude of their light on their object, so
//! a weak light keeps its relative precision (2⁻¹¹).

use half::f16;

/// What one light contributes at one vertex while maps are being built: the light's index,
/// the SH (order of the maps) of its unit-intensity radiance there (direct and indirect),
/// and the irradiance its indirect light alone gives the vertex's surface.
#[derive(Debug, Clone, PartialEq)]
pub struct LightContribution {
    pub light: u32,
    pub sh: Vec<f32>,
    /// ∫ L_indirect(ω)·max(n·ω, 0) dω at unit intensity (luminance, lux per candela of the
    /// light): what the real-time renderer adds as baked indirect light, estimated from
    /// the bounce rays themselves (no SH truncation).
    pub indirect_irradiance: f32,
}

/// How coefficients are stored. Half precision is the default: the large sample's maps
/// take 223.7 MiB in it against 408.5 MiB in f32 (docs/performance.md), within the 266 MB
/// of Rozon's wavelet maps, and three significant digits are finer than the bake's own
/// Monte Carlo noise at its default samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    F32,
    /// Half precision, scaled per (object, light): half the memory, 3 significant digits.
    #[default]
    F16,
}

/// The coefficients of one stored entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Coefficients<'a> {
    F32(&'a [f32]),
    F16 { values: &'a [f16], scale: f32 },
}

impl Coefficients<'_> {
    pub fn len(&self) -> usize {
        match self {
            Coefficients::F32(v) => v.len(),
            Coefficients::F16 { values, .. } => values.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Coefficient k (0 past the end).
    pub fn get(&self, k: usize) -> f32 {
        match self {
            Coefficients::F32(v) => v.get(k).copied().unwrap_or(0.0),
            Coefficients::F16 { values, scale } => values.get(k).map_or(0.0, |h| h.to_f32() * scale),
        }
    }

    /// The DC coefficient (the light's incident power there / (2√π)).
    pub fn dc(&self) -> f32 {
        self.get(0)
    }

    /// Σ_k c_k·basis_k.
    pub fn dot(&self, basis: &[f64]) -> f64 {
        (0..self.len().min(basis.len()))
            .map(|k| self.get(k) as f64 * basis[k])
            .sum()
    }

    pub fn to_vec(&self) -> Vec<f32> {
        (0..self.len()).map(|k| self.get(k)).collect()
    }

    pub fn all_finite(&self) -> bool {
        (0..self.len()).all(|k| self.get(k).is_finite())
    }
}

/// One stored entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapEntry<'a> {
    pub light: u32,
    pub sh: Coefficients<'a>,
    /// See [`LightContribution::indirect_irradiance`].
    pub indirect_irradiance: f32,
}

/// The maps of one object's vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectMaps {
    /// n² SH coefficients and the indirect irradiance.
    values_per_entry: usize,
    first: Vec<u32>,
    lights: Vec<u32>,
    store: RawCoefficients,
}

/// The raw arrays of an object's maps, for the cache file.
pub struct RawMaps<'a> {
    pub first: &'a [u32],
    pub lights: &'a [u32],
    pub coefficients: CoefficientArrays<'a>,
}

/// The coefficient array of an object: f32, or f16 relative to per-light scales.
pub enum CoefficientArrays<'a> {
    F32(&'a [f32]),
    F16 { values: &'a [f16], scales: &'a [f32] },
}

impl ObjectMaps {
    /// Packs per-vertex lists (each sorted by light) of order-`order` contributions.
    pub fn from_vertices(order: usize, vertices: &[Vec<LightContribution>], precision: Precision) -> ObjectMaps {
        let per_entry = order * order + 1;
        let entries: usize = vertices.iter().map(Vec::len).sum();
        let mut first = Vec::with_capacity(vertices.len() + 1);
        let mut lights = Vec::with_capacity(entries);
        first.push(0);
        for vertex in vertices {
            lights.extend(vertex.iter().map(|e| e.light));
            first.push(lights.len() as u32);
        }
        let coefficient = |e: &LightContribution, k: usize| {
            if k + 1 == per_entry {
                e.indirect_irradiance
            } else {
                e.sh.get(k).copied().unwrap_or(0.0)
            }
        };
        let store = match precision {
            Precision::F32 => RawCoefficients::F32(
                vertices
                    .iter()
                    .flatten()
                    .flat_map(|e| (0..per_entry).map(move |k| coefficient(e, k)))
                    .collect(),
            ),
            Precision::F16 => {
                let light_count = lights.iter().map(|&l| l as usize + 1).max().unwrap_or(0);
                let mut scales = vec![0.0f32; light_count];
                for e in vertices.iter().flatten() {
                    let largest = (0..per_entry).map(|k| coefficient(e, k).abs()).fold(0.0, f32::max);
                    if largest.is_finite() {
                        scales[e.light as usize] = scales[e.light as usize].max(largest);
                    }
                }
                scales.iter_mut().filter(|s| **s == 0.0).for_each(|s| *s = 1.0);
                let values = vertices
                    .iter()
                    .flatten()
                    .flat_map(|e| {
                        let scale = scales[e.light as usize];
                        (0..per_entry).map(move |k| f16::from_f32(coefficient(e, k) / scale))
                    })
                    .collect();
                RawCoefficients::F16 { values, scales }
            }
        };
        ObjectMaps {
            values_per_entry: per_entry,
            first,
            lights,
            store,
        }
    }

    pub fn precision(&self) -> Precision {
        match self.store {
            RawCoefficients::F32(_) => Precision::F32,
            RawCoefficients::F16 { .. } => Precision::F16,
        }
    }

    pub fn vertex_count(&self) -> usize {
        self.first.len().saturating_sub(1)
    }

    pub fn entry_count(&self) -> usize {
        self.lights.len()
    }

    fn entry(&self, k: usize) -> MapEntry<'_> {
        let n = self.values_per_entry;
        let light = self.lights[k];
        let (sh, indirect) = (k * n..(k + 1) * n - 1, (k + 1) * n - 1);
        let (sh, indirect_irradiance) = match &self.store {
            RawCoefficients::F32(values) => (Coefficients::F32(&values[sh]), values[indirect]),
            RawCoefficients::F16 { values, scales } => {
                let scale = scales.get(light as usize).copied().unwrap_or(1.0);
                let coefficients = Coefficients::F16 {
                    values: &values[sh],
                    scale,
                };
                (coefficients, values[indirect].to_f32() * scale)
            }
        };
        MapEntry {
            light,
            sh,
            indirect_irradiance,
        }
    }

    /// The entries of vertex `v` (none past the end), by light.
    pub fn entries(&self, v: usize) -> impl ExactSizeIterator<Item = MapEntry<'_>> + '_ {
        let range = match (self.first.get(v), self.first.get(v + 1)) {
            (Some(&a), Some(&b)) => a as usize..b as usize,
            _ => 0..0,
        };
        range.map(move |k| self.entry(k))
    }

    /// The entries of vertex `v` as owned contributions.
    pub fn contributions(&self, v: usize) -> Vec<LightContribution> {
        self.entries(v)
            .map(|e| LightContribution {
                light: e.light,
                sh: e.sh.to_vec(),
                indirect_irradiance: e.indirect_irradiance,
            })
            .collect()
    }

    /// Every vertex's entries as owned contributions (for tests and reports).
    pub fn to_vertices(&self) -> Vec<Vec<LightContribution>> {
        (0..self.vertex_count()).map(|v| self.contributions(v)).collect()
    }

    /// Every entry of every vertex.
    pub fn all_entries(&self) -> impl Iterator<Item = MapEntry<'_>> + '_ {
        (0..self.entry_count()).map(move |k| self.entry(k))
    }

    /// The maps with only the entries `keep` accepts (same precision and scales); also
    /// how many it dropped.
    pub fn filtered(&self, keep: impl Fn(&MapEntry) -> bool) -> (ObjectMaps, usize) {
        let n = self.values_per_entry;
        let mut first = Vec::with_capacity(self.first.len());
        let mut lights = Vec::with_capacity(self.lights.len());
        let mut kept = Vec::with_capacity(self.lights.len());
        first.push(0);
        for v in 0..self.vertex_count() {
            let (a, b) = (self.first[v] as usize, self.first[v + 1] as usize);
            for k in a..b {
                if keep(&self.entry(k)) {
                    lights.push(self.lights[k]);
                    kept.push(k);
                }
            }
            first.push(lights.len() as u32);
        }
        let store = match &self.store {
            RawCoefficients::F32(values) => RawCoefficients::F32(
                kept.iter()
                    .flat_map(|&k| values[k * n..(k + 1) * n].iter().copied())
                    .collect(),
            ),
            RawCoefficients::F16 { values, scales } => RawCoefficients::F16 {
                values: kept
                    .iter()
                    .flat_map(|&k| values[k * n..(k + 1) * n].iter().copied())
                    .collect(),
                scales: scales.clone(),
            },
        };
        let dropped = self.entry_count() - lights.len();
        let maps = ObjectMaps {
            values_per_entry: n,
            first,
            lights,
            store,
        };
        (maps, dropped)
    }

    pub fn raw(&self) -> RawMaps<'_> {
        let coefficients = match &self.store {
            RawCoefficients::F32(values) => CoefficientArrays::F32(values),
            RawCoefficients::F16 { values, scales } => CoefficientArrays::F16 { values, scales },
        };
        RawMaps {
            first: &self.first,
            lights: &self.lights,
            coefficients,
        }
    }

    /// Maps from raw arrays, checked: offsets rising from 0 to the entry count, lights
    /// below `light_count`, n² + 1 values per entry, a finite positive scale per light.
    pub fn from_raw(
        order: usize,
        light_count: usize,
        first: Vec<u32>,
        lights: Vec<u32>,
        coefficients: RawCoefficients,
    ) -> Result<ObjectMaps, String> {
        let per_entry = order * order + 1;
        if first.first() != Some(&0) || first.windows(2).any(|w| w[0] > w[1]) {
            return Err("vertex offsets do not rise from 0".into());
        }
        let count = match &coefficients {
            RawCoefficients::F32(v) => v.len(),
            RawCoefficients::F16 { values, scales } => {
                if scales.iter().any(|s| !(s.is_finite() && *s > 0.0)) || scales.len() > light_count {
                    return Err("bad f16 scales".into());
                }
                if lights.iter().any(|&l| l as usize >= scales.len()) {
                    return Err("an entry has no f16 scale".into());
                }
                values.len()
            }
        };
        if first.last().copied().unwrap_or(0) as usize != lights.len() || count != lights.len() * per_entry {
            return Err("entry counts do not match".into());
        }
        if let Some(light) = lights.iter().find(|&&l| l as usize >= light_count) {
            return Err(format!("an entry names light {light} of {light_count}"));
        }
        Ok(ObjectMaps {
            values_per_entry: per_entry,
            first,
            lights,
            store: coefficients,
        })
    }

    /// Bytes the maps take in memory.
    pub fn memory_bytes(&self) -> usize {
        let coefficients = match &self.store {
            RawCoefficients::F32(v) => 4 * v.len(),
            RawCoefficients::F16 { values, scales } => 2 * values.len() + 4 * scales.len(),
        };
        4 * (self.first.len() + self.lights.len()) + coefficients
    }
}

/// An object's owned coefficient array: f32, or f16 values divided by `scales[light]`.
#[derive(Debug, Clone, PartialEq)]
pub enum RawCoefficients {
    F32(Vec<f32>),
    F16 { values: Vec<f16>, scales: Vec<f32> },
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(light: u32, dc: f32) -> LightContribution {
        LightContribution {
            light,
            sh: vec![dc, 0.5, -0.25, 0.125],
            indirect_irradiance: dc / 4.0,
        }
    }

    #[test]
    fn packed_vertices_read_back_and_filter() {
        let vertices = vec![vec![c(0, 1.0), c(2, 3.0)], vec![], vec![c(1, 2.0)]];
        let maps = ObjectMaps::from_vertices(2, &vertices, Precision::F32);
        assert_eq!(maps.vertex_count(), 3);
        assert_eq!(maps.entry_count(), 3);
        assert_eq!(maps.to_vertices(), vertices);
        assert_eq!(maps.entries(7).len(), 0);
        let (kept, dropped) = maps.filtered(|e| e.sh.dc() >= 2.0);
        assert_eq!(dropped, 1);
        assert_eq!(kept.contributions(0), vec![c(2, 3.0)]);
        assert_eq!(kept.contributions(2), vec![c(1, 2.0)]);
        assert_eq!(maps.memory_bytes(), 4 * (4 + 3 + 15));
    }

    #[test]
    fn f16_maps_keep_three_digits_for_weak_and_strong_lights_alike() {
        // Light 0 is 10⁶ times weaker than light 1: its own scale (its largest magnitude
        // on the object, 1e-6) keeps its error within 2⁻¹¹ of that, not of light 1's.
        let weak = |sh: [f32; 4]| LightContribution {
            light: 0,
            sh: sh.to_vec(),
            indirect_irradiance: sh[0] / 2.0,
        };
        let vertices = vec![
            vec![weak([1e-6, 5e-7, -2.5e-7, 1.25e-7]), c(1, 1.0)],
            vec![weak([3e-7, -1e-7, 2e-8, 0.0])],
        ];
        let maps = ObjectMaps::from_vertices(2, &vertices, Precision::F16);
        for (stored, exact) in maps.to_vertices().iter().flatten().zip(vertices.iter().flatten()) {
            let largest = if exact.light == 0 { 1e-6 } else { 1.0 };
            for (a, b) in stored.sh.iter().zip(&exact.sh) {
                assert!((a - b).abs() <= largest / 2048.0, "{a} vs {b}");
            }
            let (a, b) = (stored.indirect_irradiance, exact.indirect_irradiance);
            assert!((a - b).abs() <= largest / 2048.0, "{a} vs {b}");
        }
        assert!(maps.memory_bytes() < ObjectMaps::from_vertices(2, &vertices, Precision::F32).memory_bytes());
        let (kept, _) = maps.filtered(|e| e.light == 0);
        assert_eq!(kept.precision(), Precision::F16);
        assert_eq!(kept.entry_count(), 2);
    }
}
