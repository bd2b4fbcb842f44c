//! The interactive viewer: a winit window whose `pixels` framebuffer shows the progressive
//! render beside an egui side panel. Rendering runs on its own thread (render_thread.rs);
//! this thread only handles input, copies finished passes into the framebuffer, and draws.

mod app;
mod camera_input;
mod denoised;
mod document;
mod document_actions;
mod edits;
mod event_loop;
mod gfx;
mod history;
mod image_layer;
mod input;
mod launch;
mod panel;
mod recent;
mod render_thread;
mod screenshot;
mod timing;
mod watch;

pub use launch::{Launch, Start, run};
