//! SplitMix64 (Steele, Lea & Flood 2014): a tiny deterministic generator for the fits that
//! must give the same result on every machine (OL training shapes, k-means seeding), and
//! the direction samplers the bake and the reference path tracer draw from it.

use glam::Vec3;

/// The generator; the state is its seed.
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_f64() * n as f64) as usize).min(n - 1)
    }
}

/// One well-mixed 64-bit seed from several numbers (SplitMix64's finaliser applied after
/// each): independent streams per pixel and pass from one user seed.
pub fn mix_seed(parts: &[u64]) -> u64 {
    parts
        .iter()
        .fold(0x6c69_6768_7470_6169_u64, |h, &p| SplitMix64(h ^ p).next_u64())
}

/// A cosine-distributed direction about unit `n` (pdf cos θ/π) from two uniform numbers.
pub fn cosine_direction(n: Vec3, u1: f64, u2: f64) -> Vec3 {
    let t = n.any_orthonormal_vector();
    let b = n.cross(t);
    let r = u1.sqrt() as f32;
    let phi = (u2 * std::f64::consts::TAU) as f32;
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1 as f32).max(0.0).sqrt()).normalize_or(n)
}

/// A direction about unit `axis` with density (r + 1)/(2π)·cos^r α over the sphere
/// (the normalised Phong lobe of exponent `r`), from two uniform numbers: cos α = u1^(1/(r+1)).
pub fn phong_lobe_direction(axis: Vec3, exponent: f64, u1: f64, u2: f64) -> Vec3 {
    let cos_alpha = u1.powf(1.0 / (exponent + 1.0));
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let t = axis.any_orthonormal_vector();
    let b = axis.cross(t);
    let phi = u2 * std::f64::consts::TAU;
    let local =
        t.as_dvec3() * (sin_alpha * phi.cos()) + b.as_dvec3() * (sin_alpha * phi.sin()) + axis.as_dvec3() * cos_alpha;
    local.as_vec3().normalize_or(axis)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean of cos^k α of `count` samples about +z.
    fn mean_cos_power(sample: impl Fn(f64, f64) -> Vec3, k: i32, count: usize) -> f64 {
        let mut random = SplitMix64(7);
        (0..count)
            .map(|_| (sample(random.next_f64(), random.next_f64()).z as f64).powi(k))
            .sum::<f64>()
            / count as f64
    }

    #[test]
    fn cosine_samples_have_the_moments_of_cos_over_pi() {
        // E[cos θ] = ∫cos²/π dω = 2/3 and E[cos² θ] = 1/2 for the density cos θ/π.
        let m1 = mean_cos_power(|a, b| cosine_direction(Vec3::Z, a, b), 1, 200_000);
        let m2 = mean_cos_power(|a, b| cosine_direction(Vec3::Z, a, b), 2, 200_000);
        assert!((m1 - 2.0 / 3.0).abs() < 3e-3, "{m1}");
        assert!((m2 - 0.5).abs() < 3e-3, "{m2}");
    }

    #[test]
    fn phong_samples_have_the_moments_of_the_lobe() {
        // For density (r+1)/(2π) cos^r α: E[cos α] = (r+1)/(r+2).
        for r in [0.0, 1.0, 10.0, 200.0] {
            let m = mean_cos_power(|a, b| phong_lobe_direction(Vec3::Z, r, a, b), 1, 100_000);
            let expected = (r + 1.0) / (r + 2.0);
            assert!((m - expected).abs() < 4e-3, "r {r}: {m} vs {expected}");
        }
    }

    #[test]
    fn mixed_seeds_differ_per_part() {
        assert_ne!(mix_seed(&[1, 2]), mix_seed(&[2, 1]));
        assert_ne!(mix_seed(&[0, 0]), mix_seed(&[0, 1]));
        assert_eq!(mix_seed(&[5, 9]), mix_seed(&[5, 9]));
    }
}
