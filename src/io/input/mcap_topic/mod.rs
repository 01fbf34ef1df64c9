//! MCAP files of other loggers: one topic (`--topic /imu`), numeric fields chosen by path
//! (`--column a_seat_z=linear_acceleration.z`, `data[2]` or `data.2` for array elements), for the
//! three common message encodings:
//! - `json` (schema optional),
//! - `protobuf` with its `FileDescriptorSet` in the schema record (`prost-reflect`),
//! - `cdr` with a `ros2msg` schema (ROS 2): the `.msg` text with its dependencies, decoded by the
//!   small CDR reader of [`ros2msg`] (hand-written: no maintained crate decodes CDR from a runtime
//!   schema).
//!
//! Each message is turned into a JSON value, so paths work the same for every encoding. The sample
//! times are the messages' log times (ns), or a field mapped to `t_s` (seconds, or a
//! `{sec, nanosec}` / `{seconds, nanos}` stamp); with `--fs` they are ignored. This reader is apart
//! from `crate::record::reader`, which reads wbv's own runs; both read the file through the one
//! bounded record stream of [`crate::io::mcap_stream`].

use super::{Column, Options, Raw, Timing};
use crate::error::{Error, Result};
use serde_json::Value;
use std::collections::HashMap;

mod decode;
mod messages;
pub(crate) mod ros2msg;

use crate::io::mcap_stream::check_chunks;
use decode::Decoder;
use messages::Messages;

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
