//! Ray throughput of the scene BVH alone (obvhs traversal with our triangle test), to set
//! beside the rays per second `lightpaint bake` reports for the whole bake on the same
//! scene: `cargo bench --bench bake`. Rays run between random pairs of vertices of the
//! interior sample (occlusion queries, as most of the bake's rays are), on all cores.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use lightpaint::bake::scene_bvh::SceneBvh;
use lightpaint::scene::parse_gltf;
use rayon::prelude::*;

fn rays(c: &mut Criterion) {
    let scene = parse_gltf(Path::new("interior.glb"), &lightpaint::samples::Sample::Interior.glb()).expect("interior");
    let bvh = SceneBvh::build(&scene);
    let points: Vec<Vec3> = scene.objects.iter().flat_map(|o| o.positions.iter().copied()).collect();
    // A fixed pseudo-random pairing (an LCG over the vertex list).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) as usize % points.len()
    };
    let segments: Vec<(Vec3, Vec3, f32)> = (0..100_000)
        .filter_map(|_| {
            let (a, b) = (points[next()], points[next()]);
            let d = b - a;
            let length = d.length();
            (length > 1e-3).then(|| (a, d / length, length))
        })
        .collect();
    eprintln!(
        "interior: {} triangles, {} rays per iteration",
        bvh.triangle_count(),
        segments.len()
    );
    let mut group = c.benchmark_group("bvh");
    group.throughput(Throughput::Elements(segments.len() as u64));
    group.sample_size(10);
    group.bench_function("occlusion rays between vertices (interior)", |b| {
        b.iter(|| {
            let blocked = segments
                .par_iter()
                .filter(|(origin, direction, length)| bvh.occluded(*origin, *direction, 1e-3, length - 1e-3))
                .count();
            black_box(blocked)
        })
    });
    group.finish();
}

criterion_group!(benches, rays);
criterion_main!(benches);
