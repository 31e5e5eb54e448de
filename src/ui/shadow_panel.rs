//! The inspector's "Shadows" section: on/off, SH order, exponentiation method, ε, which
//! lights take shadow maps or the exact path, how the BRDF meets the visibility, the
//! shading resolution and the terrain's horizon sampling, and the sphere blockers fitted
//! to the scene's meshes (count and fit per object).

use crate::blockers::{SceneBlockers, SphereBudget};
use crate::scene::Scene;
use crate::sh::ExpMethod;
use crate::shading::{BrdfShading, LightPaths, RenderSettings};

/// Draws the section and edits the shadow and blocker settings in place; the viewport and
/// the blocker fit follow the settings.
pub fn shadow_section(ui: &mut egui::Ui, render: &mut RenderSettings, blockers: &SceneBlockers, scene: &Scene) {
    let settings = &mut render.shadows;
    ui.checkbox(&mut settings.enabled, "log-SH soft shadows");
    ui.add_enabled_ui(settings.enabled, |ui| {
        egui::Grid::new("shadow settings").num_columns(2).show(ui, |ui| {
            ui.label("SH order");
            ui.add(egui::Slider::new(
                &mut settings.order,
                2..=crate::sh::MAX_REALTIME_ORDER,
            ))
            .on_hover_text("Bands of the visibility SH: higher is sharper and slower (n² coefficients).");
            ui.end_row();
            ui.label("ε (blocked)");
            ui.add(egui::Slider::new(&mut settings.epsilon, 0.01..=0.5).logarithmic(true))
                .on_hover_text("Log-visibility of a blocked direction is ln ε; 0.1 is the measured sweet spot.");
            ui.end_row();
            ui.checkbox(&mut settings.ratio_attenuation, "ratio attenuation r/d");
            ui.end_row();
            ui.checkbox(&mut settings.preserve_shadow_mass, "keep shadow mass")
                .on_hover_text(
                    "Scale each blocker so that its soft shadow takes the light it truly blocks; off, \
                     small blockers' soft shadows come out up to 2.5 times too dark (sharper SH shadows \
                     of small lights, though).",
                );
            ui.end_row();
            let per_vertex_fits = crate::shading::wgsl::sh::supports_per_vertex(settings.order);
            // The log-BRDF exponentiates per pixel (ShadowSettings::problems).
            ui.add_enabled_ui(per_vertex_fits && settings.brdf != BrdfShading::Log, |ui| {
                ui.checkbox(&mut settings.per_vertex, "per vertex").on_hover_text(
                    "Exponentiate at the vertices and interpolate: faster on dense meshes (orders ≤ 6; \
                     not with the log-BRDF).",
                );
            });
            if !per_vertex_fits {
                settings.per_vertex = false;
            }
            ui.end_row();
        });
        egui::ComboBox::from_label("light shadows")
            .selected_text(light_paths_label(settings.light_paths))
            .show_ui(ui, |ui| {
                for paths in [LightPaths::Auto, LightPaths::Harmonics, LightPaths::Exact] {
                    ui.selectable_value(&mut settings.light_paths, paths, light_paths_label(paths));
                }
            })
            .response
            .on_hover_text(
                "Exact: each light's visible share past every sphere, right for small lights \
                 (sharp, correct penumbrae; point lights cast hard shadows) at a cost per light. \
                 SH: soft; per pixel each light reads a visibility of its own (up to eight \
                 lights at a point, four under a sky; past that they share one, which dims lit \
                 ground among many blockers; per vertex they always share one). Auto: shadow \
                 maps for point, spot and \
                 sun lights when they are on, exact for sphere and area lights under 40° of \
                 angular radius. The selected light says which path it takes.",
            );
        if settings.light_paths == LightPaths::Auto {
            shadow_map_control(ui, &mut settings.shadow_map_size);
            ui.add(
                egui::Slider::new(
                    &mut settings.exact_light_budget,
                    0..=crate::shading::MAX_EXACT_LIGHT_BUDGET,
                )
                .text("exact lights at most"),
            )
            .on_hover_text(
                "Auto sends at most this many sphere and area lights the exact way, those \
                 whose shadows fall on most of the scene first (times their brightness); \
                 every eight cost a pass over the blockers per pixel. The others stay on \
                 the SH.",
            );
        }
        egui::ComboBox::from_label("exponentiation")
            .selected_text(method_label(settings.exp))
            .show_ui(ui, |ui| {
                for method in [ExpMethod::Dc, ExpMethod::Ol, ExpMethod::Hyb, ExpMethod::Ps(8)] {
                    ui.selectable_value(&mut settings.exp, method, method_label(method));
                }
            });
        egui::ComboBox::from_label("BRDF")
            .selected_text(brdf_label(settings.brdf))
            .show_ui(ui, |ui| {
                for brdf in BrdfShading::ALL {
                    let allowed = brdf != BrdfShading::Log || !settings.per_vertex;
                    ui.add_enabled_ui(allowed, |ui| {
                        ui.selectable_value(&mut settings.brdf, brdf, brdf_label(brdf));
                    });
                }
            })
            .response
            .on_hover_text(
                "Separate: each light's exact diffuse and Phong shading times its visibility. \
                 Log-BRDF and product carry the BRDF in the SH with the visibility (Ren et al.): \
                 the shadow follows the cosine across the light, at the cost of band-limited \
                 shading (the study measures both). Highlights sharper than the order carries \
                 stay exact. The log-BRDF needs per-pixel shading.",
            );
        egui::ComboBox::from_label("shaded pixels")
            .selected_text(downsample_label(settings.shading_downsample))
            .show_ui(ui, |ui| {
                for d in 1..=crate::shading::MAX_SHADING_DOWNSAMPLE {
                    ui.selectable_value(&mut settings.shading_downsample, d, downsample_label(d));
                }
            })
            .response
            .on_hover_text(
                "Shade one pixel in every d × d and rebuild the others from the samples on \
                 their own surface (textures stay sharp; thin objects are shaded in full). \
                 Fewer shaded pixels draw faster; per vertex ignores it.",
            );
        // Settings the GPU cannot draw (a project saved with the CPU-only reference
        // exponential, say) are said, not silently replaced.
        let problems = settings.gpu_problems();
        if !problems.is_empty() {
            ui.colored_label(
                ui.visuals().warn_fg_color,
                format!(
                    "The viewport cannot draw this ({}); it keeps the last settings it could.",
                    problems.join("; ")
                ),
            );
        }
        if scene.terrain.is_some() {
            let terrain = &mut settings.terrain;
            ui.add(
                egui::Slider::new(&mut terrain.azimuths, 3..=crate::shading::MAX_TERRAIN_AZIMUTHS)
                    .text("terrain azimuths"),
            )
            .on_hover_text("Horizon directions marched per pixel (W): more removes banding, costs linearly.");
            ui.add(
                egui::Slider::new(&mut terrain.pyramid_levels, 1..=crate::shading::MAX_TERRAIN_LEVELS)
                    .text("terrain pyramid levels"),
            )
            .on_hover_text("Far terrain is read from prefiltered coarser levels; 1 samples the finest only.");
        }
        if let SphereBudget::FitError(budget) = &mut render.blockers.budget {
            ui.add(egui::Slider::new(budget, 0.1..=0.8).text("sphere fit error budget"))
                .on_hover_text("Per mesh, the fewest spheres whose volume error is within this share.");
        }
        ui.label(format!("{} sphere blockers", blockers.sphere_count()));
        egui::CollapsingHeader::new("blocker fit").show(ui, |ui| {
            for line in blockers.report(scene) {
                ui.label(line);
            }
        });
    });
}

/// Shadow maps of the real triangles for point, spot and directional lights and small
/// sphere and area lights: off, or a size of map.
fn shadow_map_control(ui: &mut egui::Ui, size: &mut u32) {
    let label = |size: u32| match size {
        0 => "off (soft SH shadows)".to_string(),
        size => format!("{size} × {size}"),
    };
    egui::ComboBox::from_label("shadow maps")
        .selected_text(label(*size))
        .show_ui(ui, |ui| {
            for choice in [0, 512, crate::shading::SUGGESTED_SHADOW_MAP_SIZE, 2048, 4096] {
                ui.selectable_value(size, choice, label(choice));
            }
        })
        .response
        .on_hover_text(
            "Point, spot and sun shadows from the real triangles (walls, cards, thin bars \
             included), drawn into maps of this many texels per cube face of a point light \
             (spots and the sun twice as many per side while memory allows): larger maps give \
             sharper, truer edges. Off: those lights take the soft SH shadows of the sphere \
             blockers.",
        );
}

fn light_paths_label(paths: LightPaths) -> &'static str {
    match paths {
        LightPaths::Auto => "auto (default)",
        LightPaths::Harmonics => "all through the SH",
        LightPaths::Exact => "all exact",
    }
}

fn method_label(method: ExpMethod) -> String {
    match method {
        ExpMethod::Dc => "DC (fastest)".into(),
        ExpMethod::Ol => "optimal linear".into(),
        ExpMethod::Hyb => "hybrid (default)".into(),
        ExpMethod::Ps(terms) => format!("power series ({terms} terms)"),
        ExpMethod::Reference => "reference (CPU)".into(),
    }
}

fn brdf_label(brdf: BrdfShading) -> &'static str {
    match brdf {
        BrdfShading::Separate => "separate (default)",
        BrdfShading::Log => "log-BRDF in the SH",
        BrdfShading::Product => "by SH product",
    }
}

fn downsample_label(d: u32) -> String {
    match d {
        1 => "every pixel".into(),
        d => format!("1 in {d} × {d}"),
    }
}
