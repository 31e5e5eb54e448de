//! Every WGSL module the renderer can create parses and validates with naga, without a GPU:
//! the raster module and the log-SH module at every real-time order and exponentiation
//! method, and with each BRDF-in-SH variant.

use lightpaint::sh::ExpMethod;
use lightpaint::shading::{BrdfShading, wgsl};

fn validate(label: &str, source: &str) {
    let module =
        naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
}

#[test]
fn raster_module_validates() {
    validate("raster", &wgsl::raster_source());
}

#[test]
fn edge_filter_module_validates() {
    validate("edge filter", &wgsl::edge_filter_source());
}

#[test]
fn viewport_image_module_validates() {
    validate("viewport image", &wgsl::viewport_image_source());
}

#[test]
fn heat_map_module_validates() {
    validate("heat map", &wgsl::heat_map_source());
}

#[test]
fn logsh_modules_validate_at_every_order_and_method() {
    for order in 2..=lightpaint::sh::MAX_REALTIME_ORDER {
        for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(6)] {
            validate(
                &format!("logsh order {order} {method:?}"),
                &wgsl::logsh_source(order, method, BrdfShading::Separate),
            );
        }
    }
}

#[test]
fn logsh_modules_validate_with_the_brdf_in_the_sh_at_every_order() {
    for order in 2..=lightpaint::sh::MAX_REALTIME_ORDER {
        for brdf in [BrdfShading::Log, BrdfShading::Product] {
            for method in [ExpMethod::Hyb, ExpMethod::Ps(6)] {
                validate(
                    &format!("logsh order {order} {method:?} {brdf:?}"),
                    &wgsl::logsh_source(order, method, brdf),
                );
            }
        }
    }
}

#[test]
fn every_module_validates_with_only_what_it_imports() {
    // A module that uses a declaration it does not import (directly or through its
    // imports) fails here, even where the shaders that compose it also bring that in.
    let generated = wgsl::GeneratedModules::new(4, ExpMethod::Hyb, BrdfShading::Separate);
    let modules = generated.with_files();
    for module in &modules {
        let source = wgsl::compose(&[module.name], &modules).unwrap_or_else(|e| panic!("{}: {e}", module.name));
        validate(module.name, &source);
    }
}

#[test]
fn every_file_under_shaders_is_a_module() {
    let names: Vec<&str> = wgsl::FILES.iter().map(|m| m.name).collect();
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders")).unwrap() {
        let path = entry.unwrap().path();
        let stem = path.file_stem().unwrap().to_str().unwrap().to_string();
        assert!(
            names.contains(&stem.as_str()),
            "{} is not in wgsl::FILES",
            path.display()
        );
    }
}
