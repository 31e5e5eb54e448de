//! The editor window's furniture around the viewport: tool bar, outliner, status bar,
//! error window, shortcuts and drops, frame timing, the title, and a scripted close.

use super::*;

impl EditorApp {
    /// The status bar's message, as it reads now.
    pub fn status_message(&self) -> &str {
        &self.message
    }

    /// Whether the status bar shows its message faded: shown more than `FRESH_MESSAGE`
    /// ago, or the undo history changed since (a new message is fresh until the status
    /// bar has shown it).
    pub fn status_message_is_stale(&self) -> bool {
        self.message_seen.text == self.message
            && (self.message_seen.at.elapsed() > FRESH_MESSAGE
                || self.message_seen.history != (self.can_undo(), self.can_redo()))
    }

    pub(super) fn tool_bar(&mut self, ui: &mut egui::Ui) {
        let Some(painting) = self.session.as_mut().map(|s| &mut s.painting) else {
            return;
        };
        egui::Panel::top("tools").show(ui, |ui| tool_bar(ui, &mut painting.tool));
    }

    pub(super) fn outliner(&mut self, ui: &mut egui::Ui) {
        let mut action = None;
        egui::Panel::left("outliner").default_size(220.0).show(ui, |ui| {
            ui.heading("Scene");
            let Some(document) = self.session.as_ref().map(|s| &s.document) else {
                return;
            };
            let hidden: Vec<bool> = (0..document.scene.objects.len())
                .map(|i| document.hidden_objects.contains(&i))
                .collect();
            let state = OutlinerState {
                selection: self.selection,
                hidden: &hidden,
                solo: self.session.as_ref().and_then(|s| s.solo_light()),
            };
            action = outliner(ui, &document.scene, &state);
        });
        match action {
            Some(OutlinerAction::Select(selection)) => self.selection = Some(selection),
            Some(OutlinerAction::ToggleHidden(index)) => self.toggle_hidden(index),
            Some(OutlinerAction::Solo(light)) => self.solo(light),
            Some(OutlinerAction::AddLight) => self.add_light(),
            Some(OutlinerAction::ShowGltfScene(index)) => self.request_gltf_scene(index),
            None => {}
        }
    }

    pub(super) fn status_bar(&mut self, ui: &mut egui::Ui, unsaved: bool) {
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                if !self.options.hide_frame_timings {
                    let rate = match self.frame_clock.ms_per_frame() {
                        Some(ms) => format!("{:.0} fps ({ms:.1} ms)", 1000.0 / ms.max(1e-3)),
                        None => "– fps".to_string(),
                    };
                    ui.label(rate).on_hover_text(
                        "Frames per second while the view redraws (orbiting, painting, dragging); \
                         the editor at rest draws nothing and is not counted",
                    );
                    if let Some(viewport) = &self.viewport {
                        ui.label(format!("3D view sent in {:.1} ms", viewport.last_render_ms))
                            .on_hover_text(
                                "CPU time the last frame took to prepare and submit the 3D view's drawing; \
                                 the GPU's own time shows in the frame rate",
                            );
                    }
                    ui.separator();
                }
                ui.label(&self.adapter);
                ui.separator();
                if unsaved {
                    ui.colored_label(ui.visuals().warn_fg_color, "unsaved changes");
                    ui.separator();
                }
                // A message stays until another replaces it; once it is old, or the undo
                // history has changed since ("nothing to undo" after a new edit), it is
                // shown faded: it describes a moment that has passed.
                if self.message_seen.text != self.message {
                    self.message_seen = SeenMessage {
                        text: self.message.clone(),
                        at: std::time::Instant::now(),
                        history: (self.can_undo(), self.can_redo()),
                    };
                }
                let stale = self.status_message_is_stale();
                let color = if stale {
                    ui.visuals().weak_text_color()
                } else {
                    ui.visuals().text_color()
                };
                // Cut at the window's edge with an ellipsis; the whole of it on hover.
                ui.add(egui::Label::new(egui::RichText::new(&self.message).color(color)).truncate())
                    .on_hover_text(&self.message);
                if !stale {
                    ui.ctx().request_repaint_after(FRESH_MESSAGE);
                }
            });
        });
    }

    pub(super) fn error_window(&mut self, ctx: &egui::Context) {
        let Some(error) = self.error.clone() else { return };
        let mut open = true;
        egui::Window::new("Error")
            .collapsible(false)
            .open(&mut open)
            .show(ctx, |ui| {
                ui.label(&error);
                if ui.button("OK").clicked() {
                    self.error = None;
                }
            });
        if !open {
            self.error = None;
        }
    }

    pub(super) fn handle_shortcuts_and_drops(&mut self, ctx: &egui::Context) {
        let typing = ctx.egui_wants_keyboard_input();
        let new_key = ctx.input(|i| i.key_pressed(egui::Key::N) && i.modifiers.command);
        if new_key {
            self.request_new();
        }
        let (frame_key, open_key, save_key, dropped) = ctx.input(|i| {
            (
                i.key_pressed(egui::Key::F) && !i.modifiers.any(),
                i.key_pressed(egui::Key::O) && i.modifiers.command,
                i.key_pressed(egui::Key::S) && i.modifiers.command,
                i.raw.dropped_files.first().map(|f| f.path().to_path_buf()),
            )
        });
        let (undo_key, redo_key) = ctx.input(|i| {
            let z = i.key_pressed(egui::Key::Z) && i.modifiers.command;
            (
                z && !i.modifiers.shift,
                (z && i.modifiers.shift) || (i.key_pressed(egui::Key::Y) && i.modifiers.command),
            )
        });
        if !typing {
            let tool = ctx.input(|i| {
                let plain = |key| i.key_pressed(key) && !i.modifiers.any();
                [
                    (egui::Key::B, Tool::Brush(BrushKind::Positive)),
                    (egui::Key::N, Tool::Brush(BrushKind::Negative)),
                    (egui::Key::C, Tool::Brush(BrushKind::Constraint)),
                    (egui::Key::U, Tool::Brush(BrushKind::Release)),
                    (egui::Key::Escape, Tool::Navigate),
                ]
                .into_iter()
                .find(|(key, _)| plain(*key))
                .map(|(_, tool)| tool)
            });
            if let Some(tool) = tool {
                self.set_tool(tool);
            }
            if undo_key {
                self.undo();
            }
            if redo_key {
                self.redo();
            }
        }
        if frame_key && !typing {
            self.frame_selection();
        }
        if open_key {
            self.open_dialog();
        }
        if save_key {
            self.save_document();
        }
        if let Some(path) = dropped {
            self.request_open(&path);
        }
    }

    pub(super) fn track_frame_time(&mut self, ctx: &egui::Context) {
        self.frame_clock.tick(Instant::now(), ctx.requested_repaint_last_pass());
    }

    /// "NAME.lightpaint • — lightpaint" (the dot: unsaved changes), as window managers
    /// and task bars show it.
    pub(super) fn update_window_title(&mut self, ctx: &egui::Context, unsaved: bool) {
        let title = match self.session.as_ref().map(|s| &s.document) {
            Some(document) => {
                let path = document.project_path.as_ref().unwrap_or(&document.scene_path);
                let name = path.file_name().map_or("untitled".into(), |n| n.to_string_lossy());
                let mark = if unsaved { " •" } else { "" };
                format!("{name}{mark} — lightpaint")
            }
            None => "lightpaint".to_string(),
        };
        if title != self.window_title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.window_title = title;
        }
    }

    /// Measurement runs: the editor draws every frame — with the viewport's frame drawn
    /// at full quality after a light edit, or from nothing, or only the interface around
    /// the frame drawn before ([`FrameRateMeasurement`]) — and every two seconds the
    /// status bar's frame time goes to stderr with the viewport's size in pixels.
    pub(super) fn measure_frame_rate(&mut self, ctx: &egui::Context) {
        if self.options.measure_frame_rate == FrameRateMeasurement::Off {
            return;
        }
        match self.options.measure_frame_rate {
            FrameRateMeasurement::AfterLightEdit => self.upload_lights(),
            FrameRateMeasurement::NewView => {
                if let Some(viewport) = &mut self.viewport {
                    viewport.draw_anew();
                }
            }
            FrameRateMeasurement::Off | FrameRateMeasurement::InterfaceOnly => {}
        }
        let Some(viewport) = &mut self.viewport else {
            return;
        };
        ctx.request_repaint();
        let now = Instant::now();
        if self
            .frame_rate_printed_at
            .is_none_or(|at| now.duration_since(at) >= std::time::Duration::from_secs(2))
        {
            self.frame_rate_printed_at = Some(now);
            if let Some(ms) = self.frame_clock.ms_per_frame() {
                let view = viewport.view();
                eprintln!(
                    "lightpaint: {ms:.1} ms per frame ({:.1} fps), viewport {}×{} px",
                    1000.0 / ms.max(1e-3),
                    view.width_px,
                    view.height_px
                );
            }
        }
    }

    pub(super) fn scripted_close(&mut self, ctx: &egui::Context) {
        if let Some(path) = &self.options.close_when_file_exists {
            if path.exists() {
                self.closing = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
    }
}
