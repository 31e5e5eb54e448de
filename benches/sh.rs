//! SH costs: `cargo bench --bench sh`. Nanoseconds per exponentiation for each method at
//! orders 2–8, per basis evaluation, and per blocker accumulated into a log-visibility sum.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use lightpaint::sh::{self, ExpMethod};

fn log_visibility(order: usize, blockers: usize) -> Vec<f64> {
    let caps: Vec<(DVec3, f64)> = (0..blockers)
        .map(|k| {
            let t = k as f64 * 1.9 + 0.3;
            (DVec3::new(t.cos(), t.sin(), 0.5).normalize(), 0.3f64.asin())
        })
        .collect();
    sh::log_visibility(order, &caps, 0.1)
}

fn exponentiation(c: &mut Criterion) {
    let mut group = c.benchmark_group("exp");
    for order in 2..=8 {
        let f = log_visibility(order, 6);
        for method in [
            ExpMethod::Dc,
            ExpMethod::Ol,
            ExpMethod::Hyb,
            ExpMethod::Ps(8),
            ExpMethod::Reference,
        ] {
            group.bench_with_input(BenchmarkId::new(format!("{method:?}"), order), &f, |b, f| {
                b.iter(|| sh::exp(method, black_box(f)))
            });
        }
    }
    group.finish();
}

fn basis_evaluation(c: &mut Criterion) {
    let mut group = c.benchmark_group("basis");
    let dir = DVec3::new(0.3, -0.4, 0.866).normalize();
    for order in [2, 4, 8, 16] {
        group.bench_with_input(BenchmarkId::new("recurrence", order), &order, |b, &order| {
            b.iter(|| sh::basis(order, black_box(dir)))
        });
    }
    group.bench_function("unrolled/4", |b| b.iter(|| sh::basis_unrolled4(4, black_box(dir))));
    group.finish();
}

fn blocker_accumulation(c: &mut Criterion) {
    let mut group = c.benchmark_group("blocker");
    for order in [4, 8] {
        group.bench_with_input(BenchmarkId::new("cap+rotate+add", order), &order, |b, &order| {
            let mut f = vec![0.0; order * order];
            b.iter(|| {
                let cap = sh::rotate_zh(
                    &sh::cap_zh_from_ratio(order, black_box(0.25)),
                    black_box(DVec3::new(0.2, 0.3, 0.9)),
                );
                for (fi, ci) in f.iter_mut().zip(cap) {
                    *fi += ci;
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, exponentiation, basis_evaluation, blocker_accumulation);
criterion_main!(benches);
