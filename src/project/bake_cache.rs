//! The bake cache beside a project (`NAME.lightpaint.bake`): the importance maps with the
//! key of the inputs they were baked from, so a reopened project with unchanged geometry,
//! lights and settings uses them without a re-bake. The key is a BLAKE3 hash of the
//! geometry, the materials' reflectance (diffuse and glossy: the bounces read it) and the bake settings,
//! plus one hash per light of what shapes its maps (kind, position, direction, range; not
//! its intensity or colour, which the maps leave out). A cache whose scene key differs is
//! stale; one whose light hashes differ names the lights to re-bake; a file that is
//! truncated, corrupt or of another version fails its checksum or header and is never
//! trusted. Writes are atomic, and only finished bakes are written.
//!
//! Layout (little-endian): magic `LPBAKE`, u16 version, u32 length and the bake settings
//! as JSON, the 32-byte scene key, u32 light
//! count and 32 bytes per light, u32 order, u64 dropped entries, u32 object count, per
//! object the u32 lengths of its offset and light arrays, the u32 offsets and lights, a
//! storage byte (0: f32 values follow; 1: a u32 count of per-light f32 scales, the
//! scales, then f16 values), n² + 1 values per entry (the SH coefficients, then the
//! indirect irradiance; version 5 added the irradiance, version 6 bounces that see the
//! base-colour textures: caches of earlier versions are rebuilt),
//! and last the BLAKE3 hash of everything before it.

use std::path::{Path, PathBuf};

use std::sync::atomic::AtomicBool;

use crate::bake::{
    BakeSettings, CoefficientArrays, ImportanceMaps, ObjectMaps, RawCoefficients, bake_maps_counting, rebake_lights,
};
use crate::scene::Scene;

const MAGIC: &[u8; 6] = b"LPBAKE";
const VERSION: u16 = 6;

/// What the maps were baked from.
#[derive(Debug, Clone, PartialEq)]
pub struct BakeKey {
    pub scene: [u8; 32],
    pub lights: Vec<[u8; 32]>,
    /// The settings the scene hash covers (also written into the cache, so a reader that
    /// does not choose settings, like `render`, can check a cache for its scene).
    pub settings: BakeSettings,
}

impl BakeKey {
    pub fn of(scene: &Scene, settings: &BakeSettings) -> BakeKey {
        let mut hasher = blake3::Hasher::new();
        hasher.update(format!("{settings:?}").as_bytes());
        for object in &scene.objects {
            hasher.update(&(object.positions.len() as u64).to_le_bytes());
            hasher.update(bytemuck::cast_slice(&object.positions));
            hasher.update(bytemuck::cast_slice(&object.normals));
            hasher.update(bytemuck::cast_slice(&object.indices));
            // The bounces read the material's reflectance (diffuse and glossy); direct
            // light does not, so a bake without bounces survives a colour change.
            if settings.bounces > 0
                && let Some(material) = scene.materials.get(object.material)
            {
                let r = crate::bake::indirect::bounce_reflectance(material);
                for value in [r.k_d.to_array(), r.k_s.to_array(), [r.phong_exponent; 3]].as_flattened() {
                    hasher.update(&value.to_le_bytes());
                }
            }
        }
        let lights = scene.lights.iter().map(light_hash).collect();
        BakeKey {
            scene: *hasher.finalize().as_bytes(),
            lights,
            settings: *settings,
        }
    }
}

/// What a light's maps depend on, hashed: its kind and shape, position, direction and
/// range (not its name, colour or intensity: maps are per unit intensity and white).
pub fn light_hash(light: &crate::scene::Light) -> [u8; 32] {
    let l = light;
    *blake3::hash(format!("{:?}", (l.kind, l.position, l.direction, l.range)).as_bytes()).as_bytes()
}

/// The cache file of a project.
pub fn cache_path(project: &Path) -> PathBuf {
    let mut name = project.file_name().unwrap_or_default().to_os_string();
    name.push(".bake");
    project.with_file_name(name)
}

/// What looking up the cache found.
#[derive(Debug)]
pub enum CacheLookup {
    /// Baked from exactly these inputs.
    Fresh(ImportanceMaps),
    /// Same geometry and settings; the listed lights changed (re-bake only them).
    LightsChanged { maps: ImportanceMaps, lights: Vec<usize> },
    /// No cache file.
    Missing,
    /// A cache that cannot be used, and why (it will be rebuilt).
    Unusable(String),
}

pub fn save(path: &Path, key: &BakeKey, maps: &ImportanceMaps) -> std::io::Result<()> {
    let mut bytes = Vec::with_capacity(64 + maps.entry_count() * (4 + 4 * maps.order * maps.order));
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&VERSION.to_le_bytes());
    let settings = serde_json::to_vec(&key.settings).unwrap_or_default();
    put_u32(&mut bytes, settings.len());
    bytes.extend_from_slice(&settings);
    bytes.extend_from_slice(&key.scene);
    put_u32(&mut bytes, key.lights.len());
    key.lights.iter().for_each(|h| bytes.extend_from_slice(h));
    put_u32(&mut bytes, maps.order);
    bytes.extend_from_slice(&(maps.dropped_entries as u64).to_le_bytes());
    put_u32(&mut bytes, maps.objects.len());
    for object in &maps.objects {
        let raw = object.raw();
        put_u32(&mut bytes, raw.first.len());
        put_u32(&mut bytes, raw.lights.len());
        bytes.extend_from_slice(bytemuck::cast_slice(raw.first));
        bytes.extend_from_slice(bytemuck::cast_slice(raw.lights));
        match raw.coefficients {
            CoefficientArrays::F32(values) => {
                bytes.push(0);
                bytes.extend_from_slice(bytemuck::cast_slice(values));
            }
            CoefficientArrays::F16 { values, scales } => {
                bytes.push(1);
                put_u32(&mut bytes, scales.len());
                bytes.extend_from_slice(bytemuck::cast_slice(scales));
                bytes.extend_from_slice(bytemuck::cast_slice(values));
            }
        }
    }
    let checksum = blake3::hash(&bytes);
    bytes.extend_from_slice(checksum.as_bytes());
    super::replace_atomically(path, &bytes)
}

fn put_u32(bytes: &mut Vec<u8>, value: usize) {
    bytes.extend_from_slice(&(value as u32).to_le_bytes());
}

/// Reads the cache at `path` and compares it with `key`.
pub fn load(path: &Path, key: &BakeKey) -> CacheLookup {
    lookup(path, |_| key.clone())
}

/// The maps in the cache at `path` for `scene`, with whatever settings they were baked
/// (for readers that do not choose bake settings, such as `render`).
pub fn load_for_scene(path: &Path, scene: &Scene) -> CacheLookup {
    lookup(path, |settings| BakeKey::of(scene, settings))
}

/// Reads the cache at `path` and compares it with the key `key_for` gives for the bake
/// settings the cache records (the file is read and its checksum computed once).
fn lookup(path: &Path, key_for: impl FnOnce(&BakeSettings) -> BakeKey) -> CacheLookup {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return CacheLookup::Missing,
        Err(e) => return CacheLookup::Unusable(format!("{}: cannot read: {e}", path.display())),
    };
    parse(&bytes, key_for).unwrap_or_else(|reason| CacheLookup::Unusable(format!("{}: {reason}", path.display())))
}

/// Checks the magic, checksum and version; returns a reader after the header and the
/// settings the maps were baked with.
fn header(bytes: &[u8]) -> Result<(Reader<'_>, BakeSettings), String> {
    if bytes.len() < MAGIC.len() + 2 + 32 || &bytes[..MAGIC.len()] != MAGIC {
        return Err("not a lightpaint bake cache".into());
    }
    let (body, checksum) = bytes.split_at(bytes.len() - 32);
    if blake3::hash(body).as_bytes() != checksum {
        return Err("corrupt or truncated (checksum mismatch)".into());
    }
    let mut reader = Reader {
        bytes: body,
        at: MAGIC.len(),
    };
    let version = u16::from_le_bytes(reader.take(2)?.try_into().map_err(|_| "short")?);
    if version != VERSION {
        return Err(format!("cache version {version}, this build reads {VERSION}"));
    }
    let length = reader.u32()?;
    let settings =
        serde_json::from_slice(reader.take(length)?).map_err(|e| format!("unreadable bake settings: {e}"))?;
    Ok((reader, settings))
}

fn parse(bytes: &[u8], key_for: impl FnOnce(&BakeSettings) -> BakeKey) -> Result<CacheLookup, String> {
    let (mut reader, settings) = header(bytes)?;
    let key = key_for(&settings);
    let body = reader.bytes;
    let scene: [u8; 32] = reader.take(32)?.try_into().map_err(|_| "short scene key")?;
    if scene != key.scene {
        return Err("baked for other geometry, materials or settings".into());
    }
    let light_count = reader.u32()?;
    let lights: Vec<[u8; 32]> = (0..light_count)
        .map(|_| {
            reader
                .take(32)
                .and_then(|h| h.try_into().map_err(|_| "short".to_string()))
        })
        .collect::<Result<_, _>>()?;
    let order = reader.u32()?;
    if !(1..=16).contains(&order) {
        return Err(format!("order {order} is out of range"));
    }
    let dropped_entries = u64::from_le_bytes(reader.take(8)?.try_into().map_err(|_| "short")?) as usize;
    let object_count = reader.u32()?;
    let mut objects = Vec::with_capacity(object_count.min(1 << 20));
    for _ in 0..object_count {
        let offsets = reader.u32()?;
        let entries = reader.u32()?;
        let first: Vec<u32> = bytemuck::pod_collect_to_vec(reader.take(4 * offsets)?);
        let lights: Vec<u32> = bytemuck::pod_collect_to_vec(reader.take(4 * entries)?);
        let count = entries * (order * order + 1);
        let coefficients = match reader.take(1)?[0] {
            0 => RawCoefficients::F32(bytemuck::pod_collect_to_vec(reader.take(4 * count)?)),
            1 => {
                let scale_count = reader.u32()?;
                let scales = bytemuck::pod_collect_to_vec(reader.take(4 * scale_count)?);
                let values = bytemuck::pod_collect_to_vec(reader.take(2 * count)?);
                RawCoefficients::F16 { values, scales }
            }
            tag => return Err(format!("unknown coefficient storage {tag}")),
        };
        objects.push(ObjectMaps::from_raw(order, light_count, first, lights, coefficients)?);
    }
    if reader.at != body.len() {
        return Err("trailing bytes after the maps".into());
    }
    let mut maps = ImportanceMaps {
        order,
        objects,
        dropped_entries,
    };
    if lights.len() != key.lights.len() {
        return Err(format!(
            "baked for {} lights, the scene has {}",
            lights.len(),
            key.lights.len()
        ));
    }
    let changed: Vec<usize> = (0..lights.len()).filter(|&i| lights[i] != key.lights[i]).collect();
    if changed.is_empty() {
        return Ok(CacheLookup::Fresh(maps));
    }
    // The changed lights' old maps must not be used in the meantime.
    for object in &mut maps.objects {
        *object = object.filtered(|e| !changed.contains(&(e.light as usize))).0;
    }
    Ok(CacheLookup::LightsChanged { maps, lights: changed })
}

/// The maps for `scene` and `settings`, from the cache at `path` when it is fresh, else
/// baked (only the changed lights when just lights moved) and written back. None if
/// cancelled (the cache is left as it was). The second value says what happened.
pub fn bake_with_cache(
    scene: &Scene,
    settings: &BakeSettings,
    path: &Path,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<(ImportanceMaps, String)> {
    let found = load(path, &BakeKey::of(scene, settings));
    let (maps, what, fresh) = maps_from(scene, settings, found, progress, cancel)?;
    if fresh {
        return Some((maps, format!("{what} {}", path.display())));
    }
    let what = match save(path, &BakeKey::of(scene, settings), &maps) {
        Ok(()) => format!("{what}; cache written to {}", path.display()),
        Err(e) => format!("{what}; the cache could not be written to {}: {e}", path.display()),
    };
    Some((maps, what))
}

/// The cache at `path` for `scene`, counting one baked with `settings` in another
/// precision (f16 or f32 coefficients) as theirs: for readers that ask for light
/// transport, not for a storage (`lightpaint paint`). Also the settings to go on with:
/// the cache's, precision included, when it was taken.
pub fn load_in_its_precision(path: &Path, scene: &Scene, settings: &BakeSettings) -> (CacheLookup, BakeSettings) {
    let effective = std::cell::Cell::new(*settings);
    let found = lookup(path, |cached| {
        let same_but_precision = BakeSettings {
            precision: settings.precision,
            ..*cached
        } == *settings;
        if same_but_precision {
            effective.set(*cached);
        }
        BakeKey::of(scene, &effective.get())
    });
    (found, effective.get())
}

/// The maps `found` in a cache, completed (its changed lights re-baked) or replaced by a
/// bake; None if cancelled. Then what happened ("read the bake cache", "re-baked N changed
/// light(s)", "baked …") and whether the cache was fresh. Writes nothing.
pub fn maps_from(
    scene: &Scene,
    settings: &BakeSettings,
    found: CacheLookup,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Option<(ImportanceMaps, String, bool)> {
    let (maps, what) = match found {
        CacheLookup::Fresh(maps) => return Some((maps, "read the bake cache".to_string(), true)),
        CacheLookup::LightsChanged { maps, lights } => {
            let count = lights.len();
            let maps = rebake_lights(scene, settings, &maps, &lights, progress, cancel)?;
            (maps, format!("re-baked {count} changed light(s)"))
        }
        CacheLookup::Missing => bake_counting(scene, settings, progress, cancel, "baked".to_string())?,
        CacheLookup::Unusable(reason) => {
            bake_counting(scene, settings, progress, cancel, format!("baked again ({reason})"))?
        }
    };
    Some((maps, what, false))
}

/// A full bake, its `what` extended with the rays traced per second.
fn bake_counting(
    scene: &Scene,
    settings: &BakeSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
    what: String,
) -> Option<(ImportanceMaps, String)> {
    let started = std::time::Instant::now();
    let (maps, rays) = bake_maps_counting(scene, settings, progress, cancel)?;
    let seconds = started.elapsed().as_secs_f64().max(1e-9);
    Some((
        maps,
        format!("{what} ({rays} rays, {:.2} M rays/s)", rays as f64 / seconds / 1e6),
    ))
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self
            .at
            .checked_add(n)
            .filter(|&e| e <= self.bytes.len())
            .ok_or("truncated")?;
        let slice = &self.bytes[self.at..end];
        self.at = end;
        Ok(slice)
    }

    fn u32(&mut self) -> Result<usize, String> {
        let bytes: [u8; 4] = self.take(4)?.try_into().map_err(|_| "short")?;
        Ok(u32::from_le_bytes(bytes) as usize)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::bake::bake_maps;
    use crate::scene::{Light, LightKind, shapes};

    fn scene() -> Scene {
        let light = |x: f32| Light {
            name: "bulb".into(),
            kind: LightKind::Point,
            color: Vec3::ONE,
            intensity: 3.0,
            position: Vec3::new(x, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            range: None,
            locked: false,
        };
        Scene {
            objects: vec![shapes::plane(2.0, 3, 1.0).into_object("floor")],
            lights: vec![light(-1.0), light(1.0)],
            ..Default::default()
        }
    }

    #[test]
    fn a_saved_cache_reads_back_fresh_and_names_changed_lights() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint.bake");
        let mut scene = scene();
        let settings = BakeSettings::default();
        let maps = bake_maps(&scene, &settings);
        save(&path, &BakeKey::of(&scene, &settings), &maps).unwrap();
        match load(&path, &BakeKey::of(&scene, &settings)) {
            CacheLookup::Fresh(read) => assert_eq!(read, maps),
            other => panic!("{other:?}"),
        }
        // Intensity and colour do not touch the maps; moving a light does.
        scene.lights[0].intensity = 99.0;
        scene.lights[0].color = Vec3::X;
        assert!(matches!(
            load(&path, &BakeKey::of(&scene, &settings)),
            CacheLookup::Fresh(_)
        ));
        scene.lights[1].position.x = 0.5;
        match load(&path, &BakeKey::of(&scene, &settings)) {
            CacheLookup::LightsChanged { maps, lights } => {
                assert_eq!(lights, vec![1]);
                assert!(
                    maps.objects
                        .iter()
                        .flat_map(ObjectMaps::all_entries)
                        .all(|e| e.light == 0)
                );
            }
            other => panic!("{other:?}"),
        }
        let other_settings = BakeSettings { order: 4, ..settings };
        assert!(matches!(
            load(&path, &BakeKey::of(&scene, &other_settings)),
            CacheLookup::Unusable(_)
        ));
    }

    /// Direct light does not depend on the materials, so a bake without bounces stays
    /// fresh when a colour changes; a bake with bounces does not.
    #[test]
    fn materials_key_the_cache_only_when_light_bounces() {
        let mut scene = scene();
        scene.materials.push(crate::scene::Material::default());
        let key = |scene: &Scene, bounces| {
            BakeKey::of(
                scene,
                &BakeSettings {
                    bounces,
                    ..BakeSettings::default()
                },
            )
            .scene
        };
        let (direct, bounced) = (key(&scene, 0), key(&scene, 1));
        scene.materials[0].base_color = glam::Vec4::new(0.2, 0.4, 0.6, 1.0);
        assert_eq!(key(&scene, 0), direct);
        assert_ne!(key(&scene, 1), bounced);
    }

    /// `load_for_scene` finds a cache whatever settings it was baked with, and only for
    /// its own scene.
    #[test]
    fn a_cache_is_found_for_its_scene_without_knowing_its_settings() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint.bake");
        let mut scene = scene();
        let settings = BakeSettings {
            order: 2,
            bounces: 0,
            ..BakeSettings::default()
        };
        let maps = bake_maps(&scene, &settings);
        save(&path, &BakeKey::of(&scene, &settings), &maps).unwrap();
        assert!(matches!(load_for_scene(&path, &scene), CacheLookup::Fresh(read) if read == maps));
        scene.objects[0].positions[0].y += 0.5;
        assert!(matches!(load_for_scene(&path, &scene), CacheLookup::Unusable(_)));
    }

    #[test]
    fn f16_maps_round_trip_through_the_cache() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint.bake");
        let scene = scene();
        let settings = BakeSettings {
            precision: crate::bake::Precision::F16,
            ..BakeSettings::default()
        };
        let maps = bake_maps(&scene, &settings);
        save(&path, &BakeKey::of(&scene, &settings), &maps).unwrap();
        match load(&path, &BakeKey::of(&scene, &settings)) {
            CacheLookup::Fresh(read) => assert_eq!(read, maps),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_cancelled_bake_writes_no_cache_and_keeps_the_old_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint.bake");
        let scene = scene();
        let settings = BakeSettings::default();
        let cancelled = AtomicBool::new(true);
        assert!(bake_with_cache(&scene, &settings, &path, &|_, _| {}, &cancelled).is_none());
        assert!(!path.exists(), "no partial cache");
        let go = AtomicBool::new(false);
        bake_with_cache(&scene, &settings, &path, &|_, _| {}, &go).expect("baked");
        let written = std::fs::read(&path).unwrap();
        let other = BakeSettings { order: 4, ..settings };
        assert!(bake_with_cache(&scene, &other, &path, &|_, _| {}, &cancelled).is_none());
        assert_eq!(
            std::fs::read(&path).unwrap(),
            written,
            "a cancelled re-bake leaves the cache"
        );
    }

    #[test]
    fn truncated_or_corrupt_caches_are_never_trusted() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.lightpaint.bake");
        let scene = scene();
        let settings = BakeSettings::default();
        let key = BakeKey::of(&scene, &settings);
        save(&path, &key, &bake_maps(&scene, &settings)).unwrap();
        let good = std::fs::read(&path).unwrap();
        for cut in [0, 5, 40, good.len() / 2, good.len() - 1] {
            std::fs::write(&path, &good[..cut]).unwrap();
            assert!(matches!(load(&path, &key), CacheLookup::Unusable(_)), "cut at {cut}");
        }
        let mut flipped = good.clone();
        flipped[good.len() / 2] ^= 0x10;
        std::fs::write(&path, &flipped).unwrap();
        match load(&path, &key) {
            CacheLookup::Unusable(reason) => assert!(reason.contains("checksum"), "{reason}"),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            load(&dir.path().join("none.bake"), &key),
            CacheLookup::Missing
        ));
    }
}
