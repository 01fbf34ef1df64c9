//! The same scene as protobuf: `foxglove.SceneUpdate` and `foxglove.FrameTransforms` built with
//! the Foxglove SDK's generated types (`foxglove::schemas`, from the published `.proto` files) and
//! encoded by `prost`; the geometry is the JSON scene's, field for field.

use super::Scene;
use crate::record::topics::plot_key;
use crate::simulate::observer::Step;
use foxglove::Encode;
use foxglove::schemas::{
    Color, CubePrimitive, Duration, FrameTransform, FrameTransforms, KeyValuePair, LinePrimitive,
    Point3, Pose, Quaternion, SceneEntity, SceneUpdate, TextPrimitive, Timestamp, Vector3,
    line_primitive,
};

/// Schema name, encoding and serialized `FileDescriptorSet` of `foxglove.SceneUpdate`.
pub fn scene_update_schema() -> foxglove::Schema {
    SceneUpdate::get_schema().expect("the SDK ships the SceneUpdate descriptor")
}

/// Schema of `foxglove.FrameTransforms`.
pub fn frame_transforms_schema() -> foxglove::Schema {
    FrameTransforms::get_schema().expect("the SDK ships the FrameTransforms descriptor")
}

fn stamp(t: f64) -> Timestamp {
    let ns = (t * 1e9).round().max(0.0) as u64;
    Timestamp::new_checked((ns / 1_000_000_000) as u32, (ns % 1_000_000_000) as u32)
        .unwrap_or(Timestamp::MAX)
}

fn color(c: [f64; 4]) -> Option<Color> {
    Some(Color {
        r: c[0],
        g: c[1],
        b: c[2],
        a: c[3],
    })
}

fn v3(x: f64, y: f64, z: f64) -> Option<Vector3> {
    Some(Vector3 { x, y, z })
}

/// Rotation by `theta` (rad) about y.
fn quat_y(theta: f64) -> Option<Quaternion> {
    Some(Quaternion {
        x: 0.0,
        y: (0.5 * theta).sin(),
        z: 0.0,
        w: (0.5 * theta).cos(),
    })
}

fn pose(c: [f64; 2], theta: f64) -> Option<Pose> {
    Some(Pose {
        position: v3(c[0], 0.0, c[1]),
        orientation: quat_y(theta),
    })
}

fn cube(c: [f64; 2], theta: f64, size: [f64; 3], rgba: [f64; 4]) -> CubePrimitive {
    CubePrimitive {
        pose: pose(c, theta),
        size: v3(size[0], size[1], size[2]),
        color: color(rgba),
    }
}

fn text(z: f64, text: String) -> TextPrimitive {
    TextPrimitive {
        pose: pose([0.0, z], 0.0),
        billboard: true,
        font_size: 0.05,
        scale_invariant: false,
        color: color([1.0, 1.0, 1.0, 1.0]),
        text,
    }
}

impl Scene {
    fn entity(&self, t: f64) -> SceneEntity {
        SceneEntity {
            timestamp: Some(stamp(t)),
            frame_id: "world".into(),
            id: "wbv".into(),
            lifetime: Some(Duration::new_checked(0, 0).expect("zero is a duration")),
            frame_locked: false,
            metadata: vec![KeyValuePair {
                key: "display_magnification".into(),
                value: self.magnification.to_string(),
            }],
            ..Default::default()
        }
    }

    /// Appends the protobuf `foxglove.SceneUpdate` of step `s` to `out`.
    pub fn scene_update_pb(&self, s: &Step<'_>, out: &mut Vec<u8>) {
        let mut e = self.entity(s.t);
        let mut z = Vec::with_capacity(self.scene.bodies.len());
        for b in &self.scene.bodies {
            let (c, theta) = self.pose(b, s);
            z.push(c[1]);
            e.cubes.push(cube(c, theta, b.size, b.color));
        }
        for &(low, up, rgba) in &self.scene.lines {
            e.lines.push(LinePrimitive {
                r#type: line_primitive::Type::LineList as i32,
                pose: pose([0.0, 0.0], 0.0),
                thickness: 0.01,
                scale_invariant: false,
                points: vec![
                    Point3 {
                        x: 0.1,
                        y: 0.0,
                        z: z[low],
                    },
                    Point3 {
                        x: 0.1,
                        y: 0.0,
                        z: z[up],
                    },
                ],
                color: color(rgba),
                colors: Vec::new(),
                indices: Vec::new(),
            });
        }
        e.texts.push(text(
            self.scene.label_z,
            format!(
                "{} ×{} (t = {:.3} s)",
                self.scene.label, self.magnification, s.t
            ),
        ));
        let update = SceneUpdate {
            deletions: Vec::new(),
            entities: vec![e],
        };
        update.encode(out).expect("a Vec grows as needed");
    }

    /// Appends the protobuf `foxglove.FrameTransforms` of step `s` to `out`.
    pub fn frame_transforms_pb(&self, s: &Step<'_>, out: &mut Vec<u8>) {
        let ts = Some(stamp(s.t));
        let tf = |child: &str, c: [f64; 2], theta: f64| FrameTransform {
            timestamp: ts,
            parent_frame_id: "world".into(),
            child_frame_id: child.into(),
            translation: v3(c[0], 0.0, c[1]),
            rotation: quat_y(theta),
        };
        let mut transforms = vec![tf("base", [0.0, self.magnification * s.x_base], 0.0)];
        for b in self.scene.bodies.iter().filter(|b| b.frame) {
            let (c, theta) = self.pose(b, s);
            transforms.push(tf(&plot_key(&b.name), c, theta));
        }
        FrameTransforms { transforms }
            .encode(out)
            .expect("a Vec grows as needed");
    }
}
