//! Selection strategies (Rozon 2009, §8): which lights a stroke changes, from the stroke's
//! importance of every light. Ties are broken by the lower light index, so a selection is
//! a pure function of the importances (and, for Russian roulette, the seed).

use crate::random::SplitMix64;

/// How a stroke picks the lights it changes.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SelectionStrategy {
    /// The single light with the largest importance.
    #[default]
    MostImportant,
    /// The smallest set of lights, taken by decreasing importance, whose cumulative share
    /// of the total reaches `share` (in (0, 1]; Rozon's example: 0.5).
    Histogram { share: f64 },
    /// One light, drawn with probability importance / total (seeded per stroke).
    RussianRoulette,
}

impl SelectionStrategy {
    pub fn label(&self) -> &'static str {
        match self {
            SelectionStrategy::MostImportant => "most important",
            SelectionStrategy::Histogram { .. } => "histogram",
            SelectionStrategy::RussianRoulette => "Russian roulette",
        }
    }

    pub fn problems(&self) -> Vec<String> {
        match self {
            SelectionStrategy::Histogram { share } if !(*share > 0.0 && *share <= 1.0) => {
                vec![format!("histogram share must be in (0, 1], not {share}")]
            }
            _ => Vec::new(),
        }
    }
}

/// Light indices by decreasing importance (zero and non-finite importances left out).
pub fn ranked(importance: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..importance.len())
        .filter(|&i| importance[i].is_finite() && importance[i] > 0.0)
        .collect();
    order.sort_by(|&a, &b| importance[b].total_cmp(&importance[a]).then(a.cmp(&b)));
    order
}

/// The lights `strategy` picks; empty only when no light has positive importance.
pub fn select(strategy: SelectionStrategy, importance: &[f64], seed: u64) -> Vec<usize> {
    let order = ranked(importance);
    let total: f64 = order.iter().map(|&i| importance[i]).sum();
    if order.is_empty() || total.is_nan() || total <= 0.0 {
        return Vec::new();
    }
    match strategy {
        SelectionStrategy::MostImportant => vec![order[0]],
        SelectionStrategy::Histogram { share } => {
            let goal = share.clamp(0.0, 1.0) * total;
            let mut cumulative = 0.0;
            let mut chosen = Vec::new();
            for &i in &order {
                chosen.push(i);
                cumulative += importance[i];
                // The relative slack keeps share = 1 from missing the last light to rounding.
                if cumulative >= goal * (1.0 - 1e-12) {
                    break;
                }
            }
            chosen
        }
        SelectionStrategy::RussianRoulette => {
            let u = SplitMix64(seed).next_f64() * total;
            let mut cumulative = 0.0;
            for &i in &order {
                cumulative += importance[i];
                if u < cumulative {
                    return vec![i];
                }
            }
            vec![*order.last().unwrap_or(&order[0])]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn most_important_is_the_argmax_with_the_lower_index_on_ties() {
        assert_eq!(
            select(SelectionStrategy::MostImportant, &[0.1, 0.7, 0.7, 0.2], 0),
            vec![1]
        );
        assert!(select(SelectionStrategy::MostImportant, &[0.0, 0.0], 0).is_empty());
        assert!(select(SelectionStrategy::MostImportant, &[f64::NAN], 0).is_empty());
    }

    #[test]
    fn histogram_takes_the_shortest_prefix_reaching_the_share() {
        let importance = [0.1, 0.4, 0.2, 0.3];
        let histogram = |share| select(SelectionStrategy::Histogram { share }, &importance, 0);
        assert_eq!(histogram(0.5), vec![1, 3]);
        assert_eq!(histogram(0.4), vec![1]);
        assert_eq!(histogram(0.01), vec![1]);
        assert_eq!(histogram(1.0), vec![1, 3, 2, 0]);
        // Monotonic in the share.
        let mut last = 0;
        for k in 1..=100 {
            let n = histogram(k as f64 / 100.0).len();
            assert!(n >= last);
            last = n;
        }
    }

    #[test]
    fn russian_roulette_never_draws_a_light_without_importance() {
        for seed in 0..500 {
            let chosen = select(SelectionStrategy::RussianRoulette, &[0.0, 1.0, 0.0, 3.0], seed);
            assert_eq!(chosen.len(), 1);
            assert!(chosen[0] == 1 || chosen[0] == 3);
        }
    }

    /// Over many seeded strokes, each light is drawn in proportion to its importance:
    /// Pearson's χ² with 3 degrees of freedom stays below 16.27 (p = 0.001).
    #[test]
    fn russian_roulette_frequencies_match_the_importances() {
        let importance = [0.1, 0.4, 0.2, 0.3];
        let trials = 20_000u64;
        let mut counts = [0usize; 4];
        for seed in 0..trials {
            counts[select(SelectionStrategy::RussianRoulette, &importance, seed)[0]] += 1;
        }
        let chi_square: f64 = counts
            .iter()
            .zip(importance)
            .map(|(&observed, p)| {
                let expected = p * trials as f64;
                (observed as f64 - expected).powi(2) / expected
            })
            .sum();
        assert!(chi_square < 16.27, "χ² = {chi_square}, counts {counts:?}");
        // Reproducible with a fixed seed.
        assert_eq!(
            select(SelectionStrategy::RussianRoulette, &importance, 42),
            select(SelectionStrategy::RussianRoulette, &importance, 42)
        );
    }
}
