//! Every resource a shader declares sits at the slot of its name in
//! `shading::wgsl::slots`, which is also what `render` builds its bind groups from, and
//! every slot is declared by some shader: naga's reflection of each composed shader.

use std::collections::HashSet;

use lightpaint::sh::ExpMethod;
use lightpaint::shading::BrdfShading;
use lightpaint::shading::wgsl::{self, slots};

fn every_shader() -> Vec<(String, String)> {
    let mut shaders = vec![
        ("raster".to_string(), wgsl::raster_source()),
        ("heat map".to_string(), wgsl::heat_map_source()),
        ("shadow map".to_string(), wgsl::shadow_map_source()),
        ("edge filter".to_string(), wgsl::edge_filter_source()),
        ("viewport image".to_string(), wgsl::viewport_image_source()),
    ];
    for order in [2, 4, lightpaint::sh::MAX_REALTIME_ORDER] {
        shaders.push((
            format!("log-SH order {order}"),
            wgsl::logsh_source(order, ExpMethod::Hyb, BrdfShading::Separate),
        ));
    }
    shaders
}

#[test]
fn every_resource_is_at_the_slot_of_its_name_and_every_slot_is_used() {
    let mut used = HashSet::new();
    for (label, source) in every_shader() {
        let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{label}: {e}"));
        for (_, global) in module.global_variables.iter() {
            let Some(binding) = &global.binding else { continue };
            let name = global.name.as_deref().unwrap_or("(unnamed)");
            let slot = slots::ALL
                .iter()
                .find(|s| s.name == name)
                .unwrap_or_else(|| panic!("{label}: `{name}` has no slot in shading::wgsl::slots"));
            assert_eq!(
                (binding.group, binding.binding),
                (slot.group, slot.binding),
                "{label}: `{name}` is bound elsewhere than its slot"
            );
            used.insert(slot.name);
        }
    }
    for slot in slots::ALL {
        assert!(used.contains(slot.name), "no shader declares the slot `{}`", slot.name);
    }
}

#[test]
fn the_shaders_name_their_bindings_rather_than_number_them() {
    // A number in an attribute would still pass the test above while it equals the
    // slot; the names keep the two from drifting apart when a slot moves.
    for module in wgsl::FILES {
        for line in module.source.lines().filter(|l| l.contains("@binding(")) {
            let inside = line.split("@binding(").nth(1).unwrap_or("");
            assert!(
                !inside.starts_with(|c: char| c.is_ascii_digit()),
                "{}.wgsl numbers a binding: {line}",
                module.name
            );
            assert!(
                !line.contains("@group(0)")
                    && !line.contains("@group(1)")
                    && !line.contains("@group(2)")
                    && !line.contains("@group(3)"),
                "{}.wgsl numbers a group: {line}",
                module.name
            );
        }
    }
}
