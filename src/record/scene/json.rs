//! The scene in JSON: `foxglove.SceneUpdate` and `foxglove.FrameTransforms` written field by
//! field, every field the published all-required schemas ask for.

use super::Scene;
use crate::record::json::write_f64;
use crate::record::topics::plot_key;
use crate::simulate::observer::Step;
use std::io::Write;

impl Scene {
    /// The start of the one entity of a scene update at time `t` (s), up to its first cube.
    fn entity_start(&self, t: f64, out: &mut Vec<u8>) {
        let ts = stamp(t);
        let _ = write!(
            out,
            r#"{{"deletions":[],"entities":[{{"timestamp":{ts},"frame_id":"world","id":"wbv","lifetime":{{"sec":0,"nsec":0}},"frame_locked":false,"metadata":[{{"key":"display_magnification","value":""#
        );
        write_num(out, self.magnification);
        out.extend_from_slice(
            br#""}],"arrows":[],"spheres":[],"cylinders":[],"triangles":[],"models":[],"cubes":["#,
        );
    }

    /// Appends the `foxglove.SceneUpdate` JSON of step `s` to `out`.
    pub fn scene_update(&self, s: &Step<'_>, out: &mut Vec<u8>) {
        self.entity_start(s.t, out);
        let mut z = Vec::with_capacity(self.scene.bodies.len());
        for (k, b) in self.scene.bodies.iter().enumerate() {
            let (c, theta) = self.pose(b, s);
            z.push(c[1]);
            if k > 0 {
                out.push(b',');
            }
            posed_cube(out, c, theta, b.size, b.color);
        }
        out.extend_from_slice(b"],\"lines\":[");
        for (k, &(low, up, color)) in self.scene.lines.iter().enumerate() {
            if k > 0 {
                out.push(b',');
            }
            out.extend_from_slice(br#"{"type":2,"pose":"#);
            pose(out, 0.0);
            out.extend_from_slice(
                br#","thickness":0.01,"scale_invariant":false,"points":[{"x":0.1,"y":0,"z":"#,
            );
            write_num(out, z[low]);
            out.extend_from_slice(br#"},{"x":0.1,"y":0,"z":"#);
            write_num(out, z[up]);
            out.extend_from_slice(b"}],\"color\":");
            rgba(out, color);
            out.extend_from_slice(br#","colors":[],"indices":[]}"#);
        }
        out.extend_from_slice(b"],\"texts\":[{\"pose\":");
        pose(out, self.scene.label_z);
        let _ = write!(
            out,
            r#","billboard":true,"font_size":0.05,"scale_invariant":false,"color":{{"r":1,"g":1,"b":1,"a":1}},"text":"{} ×{} (t = {:.3} s)"}}]}}]}}"#,
            self.scene.label, self.magnification, s.t
        );
    }

    /// Appends the `foxglove.FrameTransforms` JSON (`world → base`, `world → <body>`) of step `s`;
    /// a body that only moves vertically is written as a plain translation.
    pub fn frame_transforms(&self, s: &Step<'_>, out: &mut Vec<u8>) {
        let ts = stamp(s.t);
        out.extend_from_slice(b"{\"transforms\":[");
        let _ = write!(
            out,
            r#"{{"timestamp":{ts},"parent_frame_id":"world","child_frame_id":"base","translation":{{"x":0,"y":0,"z":"#
        );
        write_num(out, self.magnification * s.x_base);
        out.extend_from_slice(br#"},"rotation":{"x":0,"y":0,"z":0,"w":1}}"#);
        for b in self.scene.bodies.iter().filter(|b| b.frame) {
            let (c, theta) = self.pose(b, s);
            let _ = write!(
                out,
                r#",{{"timestamp":{ts},"parent_frame_id":"world","child_frame_id":"{}","translation":"#,
                plot_key(&b.name)
            );
            let vertical = b.rest[0] == 0.0
                && b.angle == 0.0
                && b.jacobian[0].is_empty()
                && b.jacobian[2].is_empty();
            if vertical {
                out.extend_from_slice(br#"{"x":0,"y":0,"z":"#);
                write_num(out, c[1]);
                out.extend_from_slice(br#"},"rotation":{"x":0,"y":0,"z":0,"w":1}}"#);
            } else {
                vec3(out, c);
                out.extend_from_slice(br#","rotation":"#);
                quat_y(out, theta);
                out.push(b'}');
            }
        }
        out.extend_from_slice(b"]}");
    }
}

fn vec3(out: &mut Vec<u8>, c: [f64; 2]) {
    out.extend_from_slice(br#"{"x":"#);
    write_num(out, c[0]);
    out.extend_from_slice(br#","y":0,"z":"#);
    write_num(out, c[1]);
    out.push(b'}');
}

/// Unit quaternion of a rotation by `theta` (rad) about y.
fn quat_y(out: &mut Vec<u8>, theta: f64) {
    out.extend_from_slice(br#"{"x":0,"y":"#);
    write_num(out, (0.5 * theta).sin());
    out.extend_from_slice(br#","z":0,"w":"#);
    write_num(out, (0.5 * theta).cos());
    out.push(b'}');
}

fn posed_cube(out: &mut Vec<u8>, c: [f64; 2], theta: f64, size: [f64; 3], color: [f64; 4]) {
    out.extend_from_slice(br#"{"pose":{"position":"#);
    vec3(out, c);
    out.extend_from_slice(br#","orientation":"#);
    quat_y(out, theta);
    let _ = write!(
        out,
        r#"}},"size":{{"x":{},"y":{},"z":{}}},"color":"#,
        size[0], size[1], size[2]
    );
    rgba(out, color);
    out.push(b'}');
}

/// `{"sec":…,"nsec":…}` of a non-negative simulation time.
fn stamp(t: f64) -> String {
    let ns = (t * 1e9).round().max(0.0) as u64;
    format!(
        r#"{{"sec":{},"nsec":{}}}"#,
        ns / 1_000_000_000,
        ns % 1_000_000_000
    )
}

fn write_num(out: &mut Vec<u8>, v: f64) {
    // Display positions of finite states are finite; a non-finite state is refused before this.
    if write_f64(out, v).is_err() {
        out.push(b'0');
    }
}

fn pose(out: &mut Vec<u8>, z: f64) {
    out.extend_from_slice(br#"{"position":{"x":0,"y":0,"z":"#);
    write_num(out, z);
    out.extend_from_slice(br#"},"orientation":{"x":0,"y":0,"z":0,"w":1}}"#);
}

fn rgba(out: &mut Vec<u8>, c: [f64; 4]) {
    let _ = write!(
        out,
        r#"{{"r":{},"g":{},"b":{},"a":{}}}"#,
        c[0], c[1], c[2], c[3]
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::catalog;
    use crate::simulate::{Settings, layout};

    #[test]
    fn pitching_scene_is_valid_json_and_turns_only_the_moved_segment() {
        let model = catalog::resolve(catalog::PAPER_000).unwrap();
        let settings = Settings {
            dt: 1e-3,
            duration_s: 1.0,
            method: crate::integrator::Method::AVERAGE_ACCELERATION,
        };
        let lay = layout(model.system(), &settings);
        let scene = Scene::new(&lay, 20.0);
        let n = model.dof();
        let render = |x: &[f64]| {
            let zeros = vec![0.0; n];
            let step = Step {
                index: 0,
                t: 0.0,
                a_base: 0.0,
                v_base: 0.0,
                x_base: 0.0,
                x,
                v: &zeros,
                a: &zeros,
                link_deflection: &[],
                link_force: &[],
            };
            let (mut su, mut tf) = (Vec::new(), Vec::new());
            scene.scene_update(&step, &mut su);
            scene.frame_transforms(&step, &mut tf);
            let su: serde_json::Value = serde_json::from_slice(&su).unwrap();
            let tf: serde_json::Value = serde_json::from_slice(&tf).unwrap();
            (su, tf)
        };
        let rest = render(&vec![0.0; n]);
        let mut pitched = vec![0.0; n];
        pitched[3] = 0.01; // thorax pitch, rad
        let moved = render(&pitched);
        let q = |v: &serde_json::Value, i: usize| v["transforms"][i]["rotation"].clone();
        // base + 5 segments; unit quaternions; only the thorax (index 2) turns.
        assert_eq!(rest.1["transforms"].as_array().unwrap().len(), 6);
        for i in 0..6 {
            let r = q(&moved.1, i);
            let norm: f64 = ["x", "y", "z", "w"]
                .iter()
                .map(|k| r[k].as_f64().unwrap().powi(2))
                .sum();
            assert!((norm - 1.0).abs() < 1e-12);
            assert_eq!(q(&rest.1, i) == r, i != 2, "segment {i}");
        }
        let cubes = moved.0["entities"][0]["cubes"].as_array().unwrap();
        assert_eq!(cubes.len(), 7);
    }
}
