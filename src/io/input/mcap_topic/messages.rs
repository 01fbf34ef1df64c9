//! The messages of another logger's MCAP file with their channels and schemas, read from the
//! bounded record stream [`crate::io::mcap_stream::Records`].

use crate::io::mcap_stream::Records;
use std::collections::HashMap;
use std::sync::Arc;

/// The messages of an MCAP file, every record bounded to `record_limit` bytes (see
/// [`crate::io::mcap_stream`]), each with the channel (and schema) that came before it.
pub(super) struct Messages<'a> {
    records: Records<'a>,
    schemas: HashMap<u16, Arc<mcap::Schema<'static>>>,
    channels: HashMap<u16, Arc<mcap::Channel<'static>>>,
}

impl<'a> Messages<'a> {
    pub(super) fn new(buf: &'a [u8], record_limit: usize) -> Self {
        Messages {
            records: Records::new(buf, record_limit),
            schemas: HashMap::new(),
            channels: HashMap::new(),
        }
    }
}

impl Iterator for Messages<'_> {
    type Item = std::result::Result<mcap::Message<'static>, String>;

    fn next(&mut self) -> Option<Self::Item> {
        use mcap::records::Record;
        loop {
            let parsed = self.records.next_taken(|opcode, data| {
                Some(mcap::parse_record(opcode, data).map(Record::into_owned))
            })?;
            let record = match parsed {
                Ok(Ok(r)) => r,
                Ok(Err(e)) | Err(e) => return Some(Err(e.to_string())),
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
