// The triangle a full-screen pass draws with three vertices and no vertex buffer: vertex
// `index` (0, 1, 2) at (0, 0), (2, 0), (0, 2) of the viewport's unit square, so that the
// square is covered once. Imported by every such pass (the frame's deferred passes, the
// edge filter, the viewport image, a shadow-map view's clear).

// The corner of vertex `index` in the viewport's unit square (x right, y down the
// clip space's −y: normalised device coordinates are corner · 2 − 1).
fn full_screen_corner(index: u32) -> vec2<f32> {
    return vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
}
