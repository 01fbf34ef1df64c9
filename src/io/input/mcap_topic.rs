//! MCAP files of other loggers: one topic (`--topic /imu`), numeric fields chosen by path
//! (`--column a_seat_z=linear_acceleration.z`, `data[2]` or `data.2` for array elements), for the
//! three common message encodings:
//! - `json` (schema optional),
//! - `protobuf` with its `FileDescriptorSet` in the schema record (`prost-reflect`),
//! - `cdr` with a `ros2msg` schema (ROS 2): the `.msg` text with its dependencies, decoded by the
//!   small CDR reader below (hand-written: no maintained crate decodes CDR from a runtime schema).
//!
//! Each message is turned into a JSON value, so paths work the same for every encoding. The sample
//! times are the messages' log times (ns), or a field mapped to `t_s` (seconds, or a
//! `{sec, nanosec}` / `{seconds, nanos}` stamp); with `--fs` they are ignored. This reader is apart
//! from `crate::record::reader`, which reads wbv's own runs.

use super::{Column, Options, Raw, Timing};
use crate::error::{Error, Result};
use serde_json::{Map, Value};
use std::collections::HashMap;
use std::sync::Arc;

/// Largest ratio of a chunk's stated uncompressed size to its compressed size that is believed
/// (zstd and lz4 stay far below it on sensor data); a larger one is a corrupt or hostile header,
/// refused before the `mcap` crate would allocate its stated size.
const MAX_CHUNK_RATIO: u64 = 1024;

/// Checks every chunk's stated uncompressed size against its data before the messages are read;
/// returns the largest believed record length (bytes) for [`Messages`].
fn check_chunks(bytes: &[u8]) -> std::result::Result<usize, String> {
    let reader = mcap::read::LinearReader::new(bytes).map_err(|e| e.to_string())?;
    let mut largest = bytes.len();
    for rec in reader {
        match rec {
            Ok(mcap::records::Record::Chunk { header, data }) => {
                let stated = header.uncompressed_size;
                let limit = (data.len() as u64)
                    .saturating_mul(MAX_CHUNK_RATIO)
                    .max(1 << 20);
                if stated > limit {
                    return Err(format!(
                        "a chunk states {stated} bytes uncompressed from {} bytes",
                        data.len()
                    ));
                }
                largest = largest.max(usize::try_from(stated).unwrap_or(usize::MAX));
            }
            Ok(_) => {}
            Err(e) => return Err(e.to_string()),
        }
    }
    Ok(largest)
}

/// The messages of an MCAP file with every record — inside chunks too — bounded to
/// `record_limit` bytes. Written instead of `mcap::MessageStream` because that stream sets no
/// record-length limit inside chunks (mcap 0.26), so a corrupt length in a compressed chunk makes
/// it allocate the stated size and abort the process (found by fuzzing).
struct Messages<'a> {
    buf: &'a [u8],
    reader: mcap::sans_io::LinearReader,
    schemas: HashMap<u16, Arc<mcap::Schema<'static>>>,
    channels: HashMap<u16, Arc<mcap::Channel<'static>>>,
}

impl<'a> Messages<'a> {
    fn new(buf: &'a [u8], record_limit: usize) -> Self {
        Messages {
            buf,
            reader: mcap::sans_io::LinearReader::new_with_options(
                mcap::sans_io::LinearReaderOptions::default()
                    .with_record_length_limit(record_limit),
            ),
            schemas: HashMap::new(),
            channels: HashMap::new(),
        }
    }
}

impl Iterator for Messages<'_> {
    type Item = std::result::Result<mcap::Message<'static>, String>;

    fn next(&mut self) -> Option<Self::Item> {
        use mcap::records::Record;
        use mcap::sans_io::LinearReadEvent;
        loop {
            let record = match self.reader.next_event()? {
                Err(e) => return Some(Err(e.to_string())),
                Ok(LinearReadEvent::ReadRequest(need)) => {
                    let len = need.min(self.buf.len());
                    self.reader.insert(len).copy_from_slice(&self.buf[..len]);
                    self.reader.notify_read(len);
                    self.buf = &self.buf[len..];
                    continue;
                }
                Ok(LinearReadEvent::Record { data, opcode }) => {
                    match mcap::parse_record(opcode, data) {
                        Ok(r) => r.into_owned(),
                        Err(e) => return Some(Err(e.to_string())),
                    }
                }
            };
            match record {
                Record::Schema { header, data } => {
                    self.schemas.insert(
                        header.id,
                        Arc::new(mcap::Schema {
                            id: header.id,
                            name: header.name,
                            encoding: header.encoding,
                            data,
                        }),
                    );
                }
                Record::Channel(c) => {
                    let schema = match c.schema_id {
                        0 => None,
                        id => match self.schemas.get(&id) {
                            Some(s) => Some(s.clone()),
                            None => {
                                return Some(Err(format!(
                                    "channel {} refers to schema {id}, which comes nowhere before it",
                                    c.topic
                                )));
                            }
                        },
                    };
                    self.channels.insert(
                        c.id,
                        Arc::new(mcap::Channel {
                            id: c.id,
                            topic: c.topic,
                            schema,
                            message_encoding: c.message_encoding,
                            metadata: c.metadata,
                        }),
                    );
                }
                Record::Message { header, data } => {
                    let Some(channel) = self.channels.get(&header.channel_id) else {
                        return Some(Err(format!(
                            "message {} on channel {}, which comes nowhere before it",
                            header.sequence, header.channel_id
                        )));
                    };
                    return Some(Ok(mcap::Message {
                        channel: channel.clone(),
                        sequence: header.sequence,
                        log_time: header.log_time,
                        publish_time: header.publish_time,
                        data,
                    }));
                }
                _ => {}
            }
        }
    }
}

/// `topic (encoding, N messages)` for each channel of an MCAP file, for error messages; empty when
/// the file cannot be read.
pub fn topics(bytes: &[u8]) -> Vec<String> {
    std::panic::catch_unwind(|| list_topics(bytes)).unwrap_or_default()
}

fn list_topics(bytes: &[u8]) -> Vec<String> {
    let Ok(limit) = check_chunks(bytes) else {
        return Vec::new();
    };
    let s = Messages::new(bytes, limit);
    let mut seen: Vec<(String, String, usize)> = Vec::new();
    for m in s.take(1_000_000) {
        let Ok(m) = m else { break };
        match seen.iter_mut().find(|(t, _, _)| *t == m.channel.topic) {
            Some(e) => e.2 += 1,
            None => seen.push((
                m.channel.topic.clone(),
                m.channel.message_encoding.clone(),
                1,
            )),
        }
    }
    seen.into_iter()
        .map(|(t, e, n)| format!("{t} ({e}, {n} messages)"))
        .collect()
}

/// The value at `path` (`a.b[2].c` or `a.b.2.c`) inside `v`.
pub(crate) fn lookup<'v>(v: &'v Value, path: &str) -> Option<&'v Value> {
    let mut cur = v;
    for part in path.replace('[', ".").replace(']', "").split('.') {
        if part.is_empty() {
            continue;
        }
        cur = match cur {
            Value::Object(m) => m.get(part)?,
            Value::Array(a) => a.get(part.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// Paths of the numeric leaves of `v`, for error messages (at most 40).
fn numeric_paths(v: &Value, prefix: &str, out: &mut Vec<String>) {
    if out.len() >= 40 {
        return;
    }
    match v {
        Value::Number(_) => out.push(prefix.to_string()),
        Value::Object(m) => {
            for (k, x) in m {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                numeric_paths(x, &p, out);
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate().take(8) {
                numeric_paths(x, &format!("{prefix}[{i}]"), out);
            }
        }
        _ => {}
    }
}

/// A time field as (whole seconds, nanoseconds): a number of seconds, or a `{sec, nanosec}` /
/// `{seconds, nanos}` stamp, kept apart so that differences of large epoch times stay exact.
fn stamp(v: &Value) -> Option<(f64, f64)> {
    if let Some(x) = v.as_f64() {
        return Some((x, 0.0));
    }
    let m = v.as_object()?;
    let s = m.get("sec").or_else(|| m.get("seconds"))?.as_f64()?;
    let ns = m
        .get("nanosec")
        .or_else(|| m.get("nanos"))
        .or_else(|| m.get("nsec"))
        .and_then(Value::as_f64)
        .unwrap_or(0.0);
    Some((s, ns))
}

enum Decoder {
    Json,
    Protobuf(prost_reflect::MessageDescriptor),
    Cdr(ros2msg::Schema),
}

impl Decoder {
    fn new(channel: &mcap::Channel<'_>, source: &str) -> Result<Self> {
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

    fn decode(&self, data: &[u8]) -> std::result::Result<Value, String> {
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

/// Reads the mapped fields of `topic`. The `mcap` crate can panic on some corrupt chunks (a
/// capacity overflow while decompressing); that panic is turned into this file's error.
pub(crate) fn read(bytes: &[u8], source: &str, topic: &str, opts: &Options) -> Result<Raw> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        read_topic(bytes, source, topic, opts)
    }))
    .unwrap_or_else(|_| {
        Err(Error::data(
            source,
            None,
            "corrupt MCAP (the reader gave up on a chunk)",
        ))
    })
}

fn read_topic(bytes: &[u8], source: &str, topic: &str, opts: &Options) -> Result<Raw> {
    let err = |m: String| Error::data(source, None, m);
    let limit = check_chunks(bytes).map_err(|e| err(format!("corrupt MCAP: {e}")))?;
    let stream = Messages::new(bytes, limit);
    let fields: Vec<&(String, String)> = opts.columns.iter().filter(|(c, _)| c != "t_s").collect();
    let time_field = opts
        .columns
        .iter()
        .find(|(c, _)| c == "t_s")
        .map(|(_, f)| f.as_str());
    let mut decoder: Option<Decoder> = None;
    let mut data: Vec<Vec<f64>> = vec![Vec::new(); fields.len()];
    let mut t: Vec<f64> = Vec::new();
    let mut first_log: Option<u64> = None;
    let mut first_stamp: Option<(f64, f64)> = None;
    let mut count = 0usize;
    let mut other: HashMap<String, usize> = HashMap::new();
    for m in stream {
        let m = m.map_err(|e| {
            err(format!(
                "corrupt MCAP after {count} messages of {topic}: {e}"
            ))
        })?;
        if m.channel.topic != topic {
            *other.entry(m.channel.topic.clone()).or_default() += 1;
            continue;
        }
        if decoder.is_none() {
            decoder = Some(Decoder::new(&m.channel, source)?);
        }
        let value = decoder
            .as_ref()
            .expect("set")
            .decode(&m.data)
            .map_err(|e| {
                err(format!(
                    "topic {topic}: message {} undecodable: {e}",
                    count + 1
                ))
            })?;
        if fields.is_empty() {
            let mut paths = Vec::new();
            numeric_paths(&value, "", &mut paths);
            return Err(Error::parameter(
                "--column",
                format!(
                    "name the fields of {topic} to read, e.g. --column a_seat_z={}; numeric \
                     fields: {}",
                    paths.first().map_or("FIELD", String::as_str),
                    paths.join(", ")
                ),
            ));
        }
        for (k, (ch, path)) in fields.iter().enumerate() {
            let x = lookup(&value, path)
                .and_then(Value::as_f64)
                .ok_or_else(|| {
                    let mut paths = Vec::new();
                    numeric_paths(&value, "", &mut paths);
                    Error::parameter(
                        "--column",
                        format!(
                            "{ch}={path}: message {} of {topic} has no numeric field `{path}` \
                         (numeric fields: {})",
                            count + 1,
                            paths.join(", ")
                        ),
                    )
                })?;
            data[k].push(x);
        }
        match time_field {
            Some(p) => {
                let (s, ns) = lookup(&value, p).and_then(stamp).ok_or_else(|| {
                    Error::parameter(
                        "--column",
                        format!(
                            "t_s={p}: message {} of {topic} has no time there",
                            count + 1
                        ),
                    )
                })?;
                let (s0, ns0) = *first_stamp.get_or_insert((s, ns));
                t.push((s - s0) + (ns - ns0) * 1e-9);
            }
            None => {
                let first = *first_log.get_or_insert(m.log_time);
                t.push(m.log_time.wrapping_sub(first) as f64 * 1e-9);
            }
        }
        count += 1;
    }
    if count == 0 {
        let mut list: Vec<String> = other
            .into_iter()
            .map(|(t, n)| format!("{t} ({n} messages)"))
            .collect();
        list.sort();
        return Err(Error::parameter(
            "--topic",
            format!(
                "{source} has no message on `{topic}` (topics: {})",
                if list.is_empty() {
                    "none".into()
                } else {
                    list.join(", ")
                }
            ),
        ));
    }
    let columns = fields
        .iter()
        .zip(data)
        .map(|((_, path), d)| Column {
            name: path.clone(),
            data: d,
            ..Column::default()
        })
        .collect();
    Ok(Raw {
        columns,
        timing: Timing::Stamps {
            name: time_field
                .map_or_else(|| format!("{topic} log time"), |p| format!("{topic} {p}")),
            t,
        },
        lines: None,
        notes: vec![format!("{source}: {count} messages of {topic}")],
    })
}

/// ROS 2 message definitions (`ros2msg` schema text) and CDR decoding into JSON values.
pub(crate) mod ros2msg {
    use serde_json::{Map, Value};
    use std::collections::HashMap;

    #[derive(Debug, Clone)]
    enum Ty {
        Prim(&'static str),
        Str,
        Msg(String),
    }

    #[derive(Debug, Clone)]
    enum Len {
        One,
        Fixed(usize),
        Seq,
    }

    #[derive(Debug, Clone)]
    struct Field {
        name: String,
        ty: Ty,
        len: Len,
    }

    /// A message type and the types it uses, by full name `pkg/msg/Name` or `pkg/Name`.
    #[derive(Debug, Clone)]
    pub struct Schema {
        root: String,
        types: HashMap<String, Vec<Field>>,
    }

    fn prim(t: &str) -> Option<&'static str> {
        Some(match t {
            "bool" => "bool",
            "byte" | "uint8" | "char" => "uint8",
            "int8" => "int8",
            "int16" => "int16",
            "uint16" => "uint16",
            "int32" => "int32",
            "uint32" => "uint32",
            "int64" => "int64",
            "uint64" => "uint64",
            "float32" => "float32",
            "float64" => "float64",
            _ => return None,
        })
    }

    fn short(name: &str) -> String {
        // `pkg/msg/Name` and `pkg/Name` are the same type.
        let parts: Vec<&str> = name.split('/').collect();
        match parts.as_slice() {
            [p, "msg", n] => format!("{p}/{n}"),
            _ => name.to_string(),
        }
    }

    impl Schema {
        /// Parses the schema text of message type `name`.
        pub fn parse(name: &str, text: &str) -> Result<Schema, String> {
            let root = short(name);
            let pkg = root.split('/').next().unwrap_or("").to_string();
            let mut types: HashMap<String, Vec<Field>> = HashMap::new();
            let mut current = root.clone();
            let mut cur_pkg = pkg;
            let mut fields = Vec::new();
            for line in text.lines() {
                let l = line.split('#').next().unwrap_or("").trim();
                if l.starts_with("===") {
                    types.insert(std::mem::take(&mut current), std::mem::take(&mut fields));
                    continue;
                }
                if let Some(n) = l.strip_prefix("MSG:") {
                    current = short(n.trim());
                    cur_pkg = current.split('/').next().unwrap_or("").to_string();
                    continue;
                }
                if l.is_empty() {
                    continue;
                }
                let mut it = l.split_whitespace();
                let (Some(t), Some(n)) = (it.next(), it.next()) else {
                    return Err(format!("schema line `{l}`: expected TYPE NAME"));
                };
                if n.contains('=') || it.next().is_some_and(|x| x.starts_with('=')) {
                    continue; // a constant
                }
                let (base, len) = match t.find('[') {
                    Some(i) => {
                        let inner = t[i + 1..].trim_end_matches(']');
                        let len = if inner.is_empty() || inner.starts_with("<=") {
                            Len::Seq
                        } else {
                            Len::Fixed(
                                inner
                                    .parse()
                                    .ok()
                                    .filter(|&n: &usize| n <= 1 << 20)
                                    .ok_or_else(|| format!("array size in `{t}`"))?,
                            )
                        };
                        (&t[..i], len)
                    }
                    None => (t, Len::One),
                };
                let base = base.split("<=").next().unwrap_or(base);
                let ty = if let Some(p) = prim(base) {
                    Ty::Prim(p)
                } else if base == "string" || base == "wstring" {
                    Ty::Str
                } else if base == "Header" {
                    Ty::Msg("std_msgs/Header".into())
                } else if base.contains('/') {
                    Ty::Msg(short(base))
                } else {
                    Ty::Msg(format!("{cur_pkg}/{base}"))
                };
                fields.push(Field {
                    name: n.to_string(),
                    ty,
                    len,
                });
            }
            types.insert(current, fields);
            types
                .entry("builtin_interfaces/Time".into())
                .or_insert_with(|| {
                    vec![
                        Field {
                            name: "sec".into(),
                            ty: Ty::Prim("int32"),
                            len: Len::One,
                        },
                        Field {
                            name: "nanosec".into(),
                            ty: Ty::Prim("uint32"),
                            len: Len::One,
                        },
                    ]
                });
            Ok(Schema { root, types })
        }

        /// Decodes one CDR-encoded message (4-byte encapsulation header, then the fields).
        pub fn decode(&self, data: &[u8]) -> Result<Value, String> {
            if data.len() < 4 {
                return Err("shorter than the CDR encapsulation header".into());
            }
            let le = match data[1] {
                0 | 2 => false,
                1 | 3 => true,
                k => return Err(format!("CDR encapsulation kind {k}")),
            };
            let mut r = Reader {
                b: &data[4..],
                pos: 0,
                le,
                // Values a message may hold: bounds fixed arrays of empty types.
                budget: 64 * data.len() + 1024,
            };
            self.message(&self.root, &mut r, 0)
        }

        fn message(&self, name: &str, r: &mut Reader<'_>, depth: usize) -> Result<Value, String> {
            if depth > 32 {
                return Err("message types nest too deep".into());
            }
            let fields = self
                .types
                .get(name)
                .ok_or_else(|| format!("type `{name}` is not defined in the schema"))?;
            let mut out = Map::new();
            for f in fields {
                let one = |r: &mut Reader<'_>| -> Result<Value, String> {
                    r.budget = r
                        .budget
                        .checked_sub(1)
                        .ok_or("more values than the message can hold")?;
                    match &f.ty {
                        Ty::Prim(p) => r.prim(p),
                        Ty::Str => r.string(),
                        Ty::Msg(m) => self.message(m, r, depth + 1),
                    }
                };
                let v = match f.len {
                    Len::One => one(r)?,
                    Len::Fixed(n) => {
                        Value::Array((0..n).map(|_| one(r)).collect::<Result<_, _>>()?)
                    }
                    Len::Seq => {
                        let n = r.u32()? as usize;
                        if n > r.b.len() {
                            return Err(format!("sequence `{}` of {n} elements overruns", f.name));
                        }
                        Value::Array((0..n).map(|_| one(r)).collect::<Result<_, _>>()?)
                    }
                };
                out.insert(f.name.clone(), v);
            }
            Ok(Value::Object(out))
        }
    }

    struct Reader<'a> {
        b: &'a [u8],
        pos: usize,
        le: bool,
        budget: usize,
    }

    impl Reader<'_> {
        fn take(&mut self, n: usize) -> Result<&[u8], String> {
            // CDR aligns each primitive to its size, counted from after the header.
            let pad = (n - self.pos % n) % n;
            let start = self.pos + pad;
            let end = start + n;
            let s = self
                .b
                .get(start..end)
                .ok_or_else(|| "message ends inside a field".to_string())?;
            self.pos = end;
            Ok(s)
        }

        fn u32(&mut self) -> Result<u32, String> {
            let b: [u8; 4] = self.take(4)?.try_into().expect("4");
            Ok(if self.le {
                u32::from_le_bytes(b)
            } else {
                u32::from_be_bytes(b)
            })
        }

        fn string(&mut self) -> Result<Value, String> {
            let n = self.u32()? as usize;
            let s = self
                .b
                .get(self.pos..self.pos.saturating_add(n))
                .ok_or_else(|| "string overruns the message".to_string())?;
            self.pos += n;
            Ok(Value::String(
                String::from_utf8_lossy(s.strip_suffix(&[0]).unwrap_or(s)).into_owned(),
            ))
        }

        fn prim(&mut self, p: &str) -> Result<Value, String> {
            macro_rules! num {
                ($t:ty, $n:expr) => {{
                    let b: [u8; $n] = self.take($n)?.try_into().expect("size");
                    if self.le {
                        <$t>::from_le_bytes(b)
                    } else {
                        <$t>::from_be_bytes(b)
                    }
                }};
            }
            let f = |x: f64| serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number);
            Ok(match p {
                "bool" => Value::Bool(num!(u8, 1) != 0),
                "uint8" => Value::from(num!(u8, 1)),
                "int8" => Value::from(num!(i8, 1)),
                "int16" => Value::from(num!(i16, 2)),
                "uint16" => Value::from(num!(u16, 2)),
                "int32" => Value::from(num!(i32, 4)),
                "uint32" => Value::from(num!(u32, 4)),
                "int64" => Value::from(num!(i64, 8)),
                "uint64" => Value::from(num!(u64, 8)),
                "float32" => f(num!(f32, 4) as f64),
                _ => f(num!(f64, 8)),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_reach_nested_fields_and_array_elements() {
        let v: Value =
            serde_json::from_str(r#"{"linear_acceleration":{"z":9.8},"data":[1,2,3]}"#).unwrap();
        assert_eq!(lookup(&v, "linear_acceleration.z").unwrap(), 9.8);
        assert_eq!(lookup(&v, "data[2]").unwrap(), 3);
        assert_eq!(lookup(&v, "data.1").unwrap(), 2);
        assert!(lookup(&v, "nope").is_none());
    }

    #[test]
    fn cdr_of_a_ros2_imu_like_message() {
        let schema = "std_msgs/Header header\nfloat64 z\nfloat32[] w\n\
                      ================\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n";
        let s = ros2msg::Schema::parse("pkg/msg/Acc", schema).unwrap();
        // header: sec=1, nanosec=5e8, frame_id "ab"; z = 2.5; w = [1.5]
        let mut b = vec![0u8, 1, 0, 0];
        b.extend(1i32.to_le_bytes());
        b.extend(500_000_000u32.to_le_bytes());
        b.extend(3u32.to_le_bytes());
        b.extend(b"ab\0");
        b.extend([0u8; 1]); // align the f64 to 8: offset 15 → 16 (counted after the header)
        b.extend(2.5f64.to_le_bytes());
        b.extend(1u32.to_le_bytes());
        b.extend(1.5f32.to_le_bytes());
        let v = s.decode(&b).unwrap();
        assert_eq!(lookup(&v, "z").unwrap(), 2.5);
        assert_eq!(lookup(&v, "w[0]").unwrap(), 1.5);
        assert_eq!(
            stamp(lookup(&v, "header.stamp").unwrap()),
            Some((1.0, 500_000_000.0))
        );
    }
}
