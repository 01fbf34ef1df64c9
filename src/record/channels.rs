//! The channels of a run: one per time-series topic, with its schema and the encoder of its
//! messages, and the 3-D scene's two (`/wbv/scene`, `/tf`), in either encoding.

use super::Encoding;
use super::file::{McapWriter, json_channel, protobuf_channel};
use super::pipeline::Encoder;
use super::proto::{self, BatchTemplate, ProtoTemplate};
use super::scene::{self, FRAME_TRANSFORMS_SCHEMA, SCENE_UPDATE_SCHEMA};
use super::topics::{Topic, plot_key};
use crate::error::{Error, Result};
use crate::simulate::observer::Layout;

/// The channels added to a run's writer.
pub struct Channels {
    /// Each time-series topic with its channel id, in message order.
    pub topics: Vec<(Topic, u16)>,
    /// How each topic's messages are written, in `topics` order.
    pub encoders: Vec<Encoder>,
    /// Channel ids of `/wbv/scene` and `/tf`.
    pub scene: u16,
    pub transforms: u16,
}

/// Where a run's channels are created: the MCAP writer, or the live view's WebSocket server.
pub trait ChannelSink {
    /// Adds a channel on `topic` whose messages are in `encoding` (`json` with a `jsonschema`
    /// schema, or `protobuf` whose schema is the message `schema_name` of the serialized
    /// `FileDescriptorSet` `schema`); returns its id.
    fn add_channel(
        &mut self,
        topic: &str,
        encoding: Encoding,
        schema_name: &str,
        schema: &[u8],
    ) -> Result<u16>;
}

/// The MCAP writer as a [`ChannelSink`]; a failed write becomes `err(e)`.
pub struct McapSink<'a, F> {
    pub writer: &'a mut McapWriter,
    pub err: &'a F,
}

impl<F: Fn(mcap::McapError) -> Error> ChannelSink for McapSink<'_, F> {
    fn add_channel(
        &mut self,
        topic: &str,
        encoding: Encoding,
        schema_name: &str,
        schema: &[u8],
    ) -> Result<u16> {
        match encoding {
            Encoding::Json => json_channel(self.writer, topic, schema_name, schema),
            Encoding::Protobuf => protobuf_channel(self.writer, topic, schema_name, schema),
        }
        .map_err(self.err)
    }
}

/// Adds to `w` the channels of `topics` (those of `layout`, made `timed()` when `batched`) and
/// of the scene, in `encoding`.
pub fn add(
    w: &mut impl ChannelSink,
    layout: &Layout,
    topics: Vec<Topic>,
    encoding: Encoding,
    batched: bool,
) -> Result<Channels> {
    let (mut channels, mut encoders) = (Vec::new(), Vec::new());
    let (scene, transforms) = match encoding {
        Encoding::Json => {
            for t in topics {
                let schema = serde_json::to_vec(&t.schema).expect("schema serialises");
                let cid = w.add_channel(t.topic, encoding, t.schema_name, &schema)?;
                encoders.push(Encoder::Json(t.template.clone()));
                channels.push((t, cid));
            }
            let scene_id = w.add_channel(
                "/wbv/scene",
                encoding,
                "foxglove.SceneUpdate",
                SCENE_UPDATE_SCHEMA.as_bytes(),
            )?;
            let tf_id = w.add_channel(
                "/tf",
                encoding,
                "foxglove.FrameTransforms",
                FRAME_TRANSFORMS_SCHEMA.as_bytes(),
            )?;
            (scene_id, tf_id)
        }
        Encoding::Protobuf => {
            let keys = |names: &[String]| names.iter().map(|n| plot_key(n)).collect::<Vec<_>>();
            let links: Vec<(String, bool)> = (keys(&layout.links).into_iter())
                .zip(layout.link_deflection.iter().copied())
                .collect();
            let fds =
                proto::run_descriptor(&layout.measured_channels(), &keys(&layout.masses), &links)?;
            let bytes = prost::Message::encode_to_vec(&fds);
            for t in topics {
                let (name, encoder) = if batched {
                    let name = format!("{}Batch", t.schema_name);
                    let template = BatchTemplate::new(&fds, &name, &t.leaves)?;
                    (name, Encoder::Batched(template))
                } else {
                    let template = ProtoTemplate::new(&fds, t.schema_name, &t.leaves)?;
                    (t.schema_name.to_string(), Encoder::Protobuf(template))
                };
                let cid = w.add_channel(t.topic, encoding, &name, &bytes)?;
                encoders.push(encoder);
                channels.push((t, cid));
            }
            let mut ids = [0; 2];
            for (id, (topic, schema)) in ids.iter_mut().zip([
                ("/wbv/scene", scene::pb::scene_update_schema()),
                ("/tf", scene::pb::frame_transforms_schema()),
            ]) {
                *id = w.add_channel(topic, encoding, &schema.name, &schema.data)?;
            }
            (ids[0], ids[1])
        }
    };
    Ok(Channels {
        topics: channels,
        encoders,
        scene,
        transforms,
    })
}
