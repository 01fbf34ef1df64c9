//! Message decoders by encoding (`json`, `protobuf` with its descriptor set, `cdr` with a
//! `ros2msg` schema), each message turned into a JSON value.

use super::ros2msg;
use crate::error::{Error, Result};
use serde_json::{Map, Value};

pub(super) enum Decoder {
    Json,
    Protobuf(prost_reflect::MessageDescriptor),
    Cdr(ros2msg::Schema),
}

impl Decoder {
    pub(super) fn new(channel: &mcap::Channel<'_>, source: &str) -> Result<Self> {
        let err = |m: String| Error::data(source, None, format!("topic {}: {m}", channel.topic));
        match channel.message_encoding.as_str() {
            "json" => Ok(Decoder::Json),
            "protobuf" => {
                let s = channel
                    .schema
                    .as_ref()
                    .ok_or_else(|| err("protobuf channel without a schema".into()))?;
                let pool = prost_reflect::DescriptorPool::decode(s.data.as_ref())
                    .map_err(|e| err(format!("protobuf schema unreadable: {e}")))?;
                let desc = pool.get_message_by_name(&s.name).ok_or_else(|| {
                    err(format!("message type `{}` is not in its schema", s.name))
                })?;
                Ok(Decoder::Protobuf(desc))
            }
            "cdr" => {
                let s = channel
                    .schema
                    .as_ref()
                    .filter(|s| s.encoding == "ros2msg")
                    .ok_or_else(|| err("cdr channel without a ros2msg schema".into()))?;
                let text = std::str::from_utf8(&s.data)
                    .map_err(|_| err("ros2msg schema is not UTF-8".into()))?;
                Ok(Decoder::Cdr(
                    ros2msg::Schema::parse(&s.name, text).map_err(err)?,
                ))
            }
            other => Err(err(format!(
                "message encoding `{other}`; json, protobuf or cdr (ros2msg) expected"
            ))),
        }
    }

    pub(super) fn decode(&self, data: &[u8]) -> std::result::Result<Value, String> {
        match self {
            Decoder::Json => serde_json::from_slice(data).map_err(|e| e.to_string()),
            Decoder::Protobuf(desc) => prost_reflect::DynamicMessage::decode(desc.clone(), data)
                .map(|m| proto_to_json(&m))
                .map_err(|e| e.to_string()),
            Decoder::Cdr(schema) => schema.decode(data),
        }
    }
}

fn proto_value(v: &prost_reflect::Value) -> Value {
    use prost_reflect::Value as P;
    match v {
        P::Bool(b) => Value::Bool(*b),
        P::I32(x) => Value::from(*x),
        P::I64(x) => Value::from(*x),
        P::U32(x) => Value::from(*x),
        P::U64(x) => Value::from(*x),
        P::F32(x) => serde_json::Number::from_f64(*x as f64).map_or(Value::Null, Value::Number),
        P::F64(x) => serde_json::Number::from_f64(*x).map_or(Value::Null, Value::Number),
        P::String(s) => Value::String(s.clone()),
        P::EnumNumber(x) => Value::from(*x),
        P::Message(m) => proto_to_json(m),
        P::List(l) => Value::Array(l.iter().map(proto_value).collect()),
        P::Bytes(_) | P::Map(_) => Value::Null,
    }
}

fn proto_to_json(m: &prost_reflect::DynamicMessage) -> Value {
    let mut out = Map::new();
    use prost_reflect::ReflectMessage;
    for fd in m.descriptor().fields() {
        out.insert(fd.name().to_string(), proto_value(&m.get_field(&fd)));
    }
    Value::Object(out)
}
