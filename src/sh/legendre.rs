//! Legendre polynomials by Bonnet's three-term recurrence, stable for |x| ≤ 1 at any degree.

/// P_0(x) … P_{count−1}(x):  (l+1)·P_{l+1} = (2l+1)·x·P_l − l·P_{l−1}.
pub fn legendre(count: usize, x: f64) -> Vec<f64> {
    let mut p = Vec::with_capacity(count);
    for l in 0..count {
        let value = match l {
            0 => 1.0,
            1 => x,
            _ => {
                let k = (l - 1) as f64;
                ((2.0 * k + 1.0) * x * p[l - 1] - k * p[l - 2]) / (k + 1.0)
            }
        };
        p.push(value);
    }
    p
}

/// P_0′(x) … P_{count−1}′(x) by P_{l+1}′ = P_{l−1}′ + (2l+1)·P_l, which has no division by
/// 1 − x² and so stays exact at the poles (P_l′(1) = l(l+1)/2).
pub fn legendre_derivative(count: usize, x: f64) -> Vec<f64> {
    let p = legendre(count, x);
    let mut d = Vec::with_capacity(count);
    for l in 0..count {
        let value = match l {
            0 => 0.0,
            1 => 1.0,
            _ => d[l - 2] + (2.0 * (l - 1) as f64 + 1.0) * p[l - 1],
        };
        d.push(value);
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_closed_forms() {
        for &x in &[-1.0, -0.3, 0.0, 0.7, 1.0] {
            let p = legendre(5, x);
            let d = legendre_derivative(5, x);
            let expected = [1.0, x, 0.5 * (3.0 * x * x - 1.0), 0.5 * (5.0 * x * x * x - 3.0 * x)];
            let expected_d = [
                0.0,
                1.0,
                3.0 * x,
                0.5 * (15.0 * x * x - 3.0),
                0.5 * (35.0 * x * x * x - 15.0 * x),
            ];
            for l in 0..4 {
                assert!((p[l] - expected[l]).abs() < 1e-14);
            }
            for l in 0..5 {
                assert!((d[l] - expected_d[l]).abs() < 1e-13, "P'_{l}({x})");
            }
        }
    }

    #[test]
    fn derivative_at_the_pole_is_l_l_plus_1_over_2() {
        let d = legendre_derivative(40, 1.0);
        for (l, value) in d.iter().enumerate() {
            let expected = (l * (l + 1)) as f64 / 2.0;
            assert!((value - expected).abs() <= 1e-12 * expected.max(1.0));
        }
    }
}
