//! The alias table (Walker 1977, built by Vose's method, 1991) by which every ray picks an
//! emitter in proportion to its power in O(1): entry i keeps itself with its probability and
//! otherwise gives way to its alias (`pick_emitter` in shaders/scene.wgsl).

/// For weights w (≥ 0, not all 0): per entry, the chance that a pick landing on it keeps it,
/// and its alias. A uniform entry, then a uniform draw against its chance, picks i with
/// probability wᵢ / Σw.
pub fn table(weights: &[f32]) -> Vec<(f32, u32)> {
    let n = weights.len();
    let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
    if n == 0 || total <= 0.0 {
        // Nothing to weigh: every entry keeps itself (a uniform pick).
        return (0..n as u32).map(|i| (1.0, i)).collect();
    }
    // Each entry's weight in units of the mean: below 1 it lends its room to an alias.
    let mut scaled: Vec<f64> = weights
        .iter()
        .map(|&w| w.max(0.0) as f64 * n as f64 / total)
        .collect();
    let mut out: Vec<(f32, u32)> = (0..n as u32).map(|i| (1.0, i)).collect();
    let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| scaled[i] < 1.0);
    while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
        small.pop();
        out[s] = (scaled[s] as f32, l as u32);
        scaled[l] -= 1.0 - scaled[s];
        if scaled[l] < 1.0 {
            large.pop();
            small.push(l);
        }
    }
    // What remains is 1 up to rounding: those entries keep themselves.
    out
}

/// The probability the table picks each entry: what the GPU's pick does, summed exactly.
#[cfg(test)]
pub fn pick_probabilities(table: &[(f32, u32)]) -> Vec<f64> {
    let n = table.len() as f64;
    let mut p = vec![0.0; table.len()];
    for (i, &(keep, alias)) in table.iter().enumerate() {
        let keep = keep.clamp(0.0, 1.0) as f64;
        p[i] += keep / n;
        p[alias as usize] += (1.0 - keep) / n;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table's pick probabilities sum to 1, follow the weights within rounding, and reach
    /// every emitter with power (and none without), for weights spread over seven orders of
    /// magnitude, equal weights, and a single emitter.
    #[test]
    fn the_alias_table_picks_each_emitter_in_proportion_to_its_power() {
        let mut random = irradiant_scene::xorshift(0x9e37_79b9);
        let spread: Vec<f32> = (0..1000)
            .map(|i| {
                if i % 97 == 0 {
                    0.0
                } else {
                    10f32.powf(7.0 * random() - 3.0)
                }
            })
            .collect();
        for weights in [spread, vec![2.5; 960], vec![7.0]] {
            let p = pick_probabilities(&table(&weights));
            let total: f64 = weights.iter().map(|&w| w as f64).sum();
            assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-9);
            for (i, (&w, &pi)) in weights.iter().zip(&p).enumerate() {
                let expected = w as f64 / total;
                assert!(
                    (pi - expected).abs() <= 1e-6 * expected.max(1.0 / weights.len() as f64),
                    "emitter {i}: picked with {pi}, its power's share is {expected}"
                );
                assert_eq!(
                    pi > 0.0,
                    w > 0.0,
                    "emitter {i} of weight {w}: probability {pi}"
                );
            }
        }
    }
}
