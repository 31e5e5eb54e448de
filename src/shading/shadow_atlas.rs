//! Where each shadow-map view lies in the map array: the lights' views share one
//! `Depth32Float` array, and a view takes a whole layer or a quadrant of one.
//!
//! A spot, the sun and a light aimed at the scene see everything they shadow through one
//! view, a point light through six cube faces. So that the views that carry a scene's
//! key shadows are sharper at the same memory, a layer is twice the setting
//! (`ShadowSettings::shadow_map_size`, a cube face's side) on a side: a single view takes
//! a whole layer (2 × the setting per side), and cube faces take a quadrant each (the
//! setting), four to a layer. The study measured why (docs/speed-accuracy.md): 2048²
//! maps against 1024² took the studio's shadowed-pixel RMSE from 0.0167 to 0.0127 and
//! the sample's from 0.0221 to 0.0173, at the same frame time, but at 16 MiB a view the
//! studio's 24 views would take 384 MiB; single views at 2048² and faces at 1024² take
//! 176 MiB.
//!
//! When that layout would cost more than [`DOUBLED_LAYOUT_BUDGET_BYTES`] (and more than
//! one view per layer at the setting's size), or its layers would exceed
//! [`MAX_LAYER_SIZE`], every view takes a whole layer of the setting's size instead: a
//! scene of many spots keeps the memory it had.

/// The most memory the doubled layout may take when it costs more than a layer per view
/// at the setting's size would.
pub const DOUBLED_LAYOUT_BUDGET_BYTES: u64 = 256 << 20;

/// The widest layer the array may have: wgpu's default `max_texture_dimension_2d`, which
/// the renderer asks of the device.
pub const MAX_LAYER_SIZE: u32 = 8192;

/// Bytes of one texel (`Depth32Float`).
const BYTES_PER_TEXEL: u64 = 4;

/// The array's shape and a cursor placing views in it, in view order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShadowAtlas {
    /// Texels per side of a layer.
    pub layer_size: u32,
    /// Layers placed so far.
    pub layers: u32,
    /// Single views take a whole layer and cube faces a quadrant (the doubled layout);
    /// false: every view a whole layer.
    doubled: bool,
    /// The layer whose quadrants are being filled, and how many are taken.
    open_quadrants: Option<(u32, u32)>,
    /// The views the layout was made for.
    single_views: usize,
    cube_faces: usize,
}

impl ShadowAtlas {
    /// The layout for `single_views` single views and `cube_faces` cube faces whose side
    /// the setting makes `face_size` texels (see the module's documentation).
    pub fn new(single_views: usize, cube_faces: usize, face_size: u32) -> ShadowAtlas {
        let face_size = face_size.max(1);
        let layer_bytes = |side: u64| side * side * BYTES_PER_TEXEL;
        let plain = (single_views + cube_faces) as u64 * layer_bytes(face_size as u64);
        let doubled_layers = (single_views + cube_faces.div_ceil(4)) as u64;
        let doubled = doubled_layers * layer_bytes(2 * face_size as u64);
        let fits = 2 * face_size <= MAX_LAYER_SIZE && doubled <= plain.max(DOUBLED_LAYOUT_BUDGET_BYTES);
        ShadowAtlas {
            layer_size: if fits { 2 * face_size } else { face_size },
            layers: 0,
            doubled: fits,
            open_quadrants: None,
            single_views,
            cube_faces,
        }
    }

    /// The side in texels of a single view (`cube_face` false) or a cube face.
    pub fn view_size(&self, cube_face: bool) -> u32 {
        if self.doubled && cube_face {
            self.layer_size / 2
        } else {
            self.layer_size
        }
    }

    /// Places the next view: `GpuShadowView::atlas` (corner u, corner v, side, layer).
    pub fn place(&mut self, cube_face: bool) -> [f32; 4] {
        if !(self.doubled && cube_face) {
            self.layers += 1;
            return [0.0, 0.0, 1.0, (self.layers - 1) as f32];
        }
        let (layer, taken) = match self.open_quadrants {
            Some((layer, taken)) if taken < 4 => (layer, taken),
            _ => {
                self.layers += 1;
                (self.layers - 1, 0)
            }
        };
        self.open_quadrants = Some((layer, taken + 1));
        let corner = |bit: u32| if taken & bit != 0 { 0.5 } else { 0.0 };
        [corner(1), corner(2), 0.5, layer as f32]
    }

    /// The array's memory in bytes once every view is placed.
    pub fn bytes(&self) -> u64 {
        self.layers as u64 * (self.layer_size as u64).pow(2) * BYTES_PER_TEXEL
    }

    /// The views' sizes and the array's memory in words, e.g. "6 views at 2048², 18 cube
    /// faces at 1024², 176 MiB" (once every view is placed).
    pub fn in_words(&self) -> String {
        let mut parts = Vec::new();
        if self.single_views > 0 {
            let side = self.view_size(false);
            parts.push(format!("{} view(s) at {side}²", self.single_views));
        }
        if self.cube_faces > 0 {
            let side = self.view_size(true);
            parts.push(format!("{} cube faces at {side}²", self.cube_faces));
        }
        if parts.is_empty() {
            return "no views".to_string();
        }
        format!(
            "{}, {:.0} MiB",
            parts.join(", "),
            self.bytes() as f64 / (1u64 << 20) as f64
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_views_take_whole_doubled_layers_and_faces_share_them_four_to_one() {
        // The studio's lights: five spots and the sun, three point lights.
        let mut atlas = ShadowAtlas::new(6, 18, 1024);
        assert_eq!(atlas.layer_size, 2048);
        let mut slots = Vec::new();
        for k in 0..24 {
            let face = (6..24).contains(&k);
            slots.push((atlas.view_size(face), atlas.place(face)));
        }
        assert!(slots[..6].iter().all(|(size, slot)| *size == 2048 && slot[2] == 1.0));
        assert!(slots[6..].iter().all(|(size, slot)| *size == 1024 && slot[2] == 0.5));
        assert_eq!(atlas.layers, 6 + 5, "18 faces in 4½ layers");
        assert_eq!(atlas.bytes(), 11 * (16 << 20));
        assert_eq!(atlas.in_words(), "6 view(s) at 2048², 18 cube faces at 1024², 176 MiB");
        // No two views overlap: each quadrant of each layer taken at most once.
        let mut taken = std::collections::HashSet::new();
        for (_, [u, v, side, layer]) in &slots {
            let quadrants: Vec<(u32, u32)> = if *side == 1.0 {
                vec![(0, 0), (0, 1), (1, 0), (1, 1)]
            } else {
                vec![((u * 2.0) as u32, (v * 2.0) as u32)]
            };
            for (i, j) in quadrants {
                assert!(
                    taken.insert((*layer as u32, i, j)),
                    "layer {layer} quadrant {i},{j} twice"
                );
            }
        }
    }

    #[test]
    fn many_single_views_keep_a_layer_each_at_the_settings_size() {
        // 40 spots at 2048² would take 640 MiB against 160 MiB at 1024².
        let mut atlas = ShadowAtlas::new(40, 0, 1024);
        assert_eq!((atlas.layer_size, atlas.view_size(false)), (1024, 1024));
        for _ in 0..40 {
            assert_eq!(atlas.place(false)[2], 1.0);
        }
        assert_eq!(atlas.bytes(), 40 * (4 << 20));
        // Faces alone cost the same either way: four to a doubled layer.
        let atlas = ShadowAtlas::new(0, 96, 1024);
        assert_eq!(atlas.view_size(true), 1024);
        // A setting whose doubled layer the device cannot hold.
        assert_eq!(ShadowAtlas::new(1, 0, 8192).layer_size, 8192);
    }
}
