//! The MCAP container: channels with their schemas, messages, and one chunk per frame.
//!
//! Each frame's messages form one zstd-compressed chunk, closed and flushed to the operating system when the frame
//! ends. A run that is killed or fails therefore leaves a file that readers can stream up to its last whole frame;
//! only [`McapFile::finish`] writes the summary and footer that indexed readers need for seeking.

use crate::RecordError;
use foxglove::Encode;
use mcap::records::{MessageHeader, Metadata};
use mcap::{Attachment, WriteOptions, Writer};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// A message channel: its id in the file and its topic (for error messages).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Channel {
    id: u16,
    topic: &'static str,
}

/// An MCAP file being written.
///
/// mcap's `Writer` finishes the file when it is dropped and panics if its output failed before (the first write to a
/// full disk, say): a writer that returned an error is therefore forgotten rather than dropped ([`Self::with`]), and
/// every later call reports that the recording failed earlier.
pub(crate) struct McapFile {
    /// The writer; `None` after an error.
    writer: Option<Writer<BufWriter<File>>>,
    path: PathBuf,
    sequence: u32,
    buffer: Vec<u8>,
}

impl McapFile {
    /// Creates (or truncates) `path` and writes the MCAP header. `library` names the writing program.
    pub fn create(path: &Path, library: &str) -> Result<Self, RecordError> {
        let file = File::create(path).map_err(|source| RecordError::Io { path: path.display().to_string(), source })?;
        let options = WriteOptions::new()
            .compression(Some(mcap::Compression::Zstd))
            .chunk_size(None)
            .compression_threads(0)
            .library(library);
        match options.create(BufWriter::new(file)) {
            Ok(writer) => Ok(Self { writer: Some(writer), path: path.to_path_buf(), sequence: 0, buffer: Vec::new() }),
            Err(source) => Err(RecordError::Mcap { path: path.display().to_string(), source }),
        }
    }

    /// Runs `operation` on the writer. After an error the writer is forgotten, not dropped (see the type's docs):
    /// its buffers leak, once, on a path that ends the recording anyway.
    fn with<T>(
        &mut self,
        operation: impl FnOnce(&mut Writer<BufWriter<File>>) -> Result<T, mcap::McapError>,
    ) -> Result<T, RecordError> {
        let Some(writer) = self.writer.as_mut() else { return Err(self.failed_earlier()) };
        operation(writer).map_err(|source| {
            std::mem::forget(self.writer.take());
            RecordError::Mcap { path: self.path.display().to_string(), source }
        })
    }

    /// The error of a call after an earlier write failed.
    fn failed_earlier(&self) -> RecordError {
        RecordError::Io {
            path: self.path.display().to_string(),
            source: std::io::Error::other("an earlier write to the recording failed"),
        }
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Adds a channel for messages of the Foxglove well-known type `M` (protobuf).
    pub fn add_protobuf_channel<M: Encode>(&mut self, topic: &'static str) -> Result<Channel, RecordError> {
        let schema =
            M::get_schema().ok_or_else(|| RecordError::Encode { topic, reason: "type has no schema".into() })?;
        let schema_id = self.with(|w| w.add_schema(&schema.name, &schema.encoding, &schema.data))?;
        let id = self.with(|w| w.add_channel(schema_id, topic, &M::get_message_encoding(), &BTreeMap::new()))?;
        Ok(Channel { id, topic })
    }

    /// Adds a channel of JSON messages described by the JSON schema `schema` named `schema_name`.
    pub fn add_json_channel(
        &mut self,
        topic: &'static str,
        schema_name: &str,
        schema: &str,
    ) -> Result<Channel, RecordError> {
        let schema_id = self.with(|w| w.add_schema(schema_name, "jsonschema", schema.as_bytes()))?;
        let id = self.with(|w| w.add_channel(schema_id, topic, "json", &BTreeMap::new()))?;
        Ok(Channel { id, topic })
    }

    /// Writes a protobuf message at `log_time` (ns).
    pub fn write_protobuf<M: Encode>(
        &mut self,
        channel: Channel,
        log_time: u64,
        message: &M,
    ) -> Result<(), RecordError> {
        let mut buffer = std::mem::take(&mut self.buffer);
        buffer.clear();
        let encoded = message.encode(&mut buffer);
        let result = match encoded {
            Ok(()) => self.write_bytes(channel, log_time, &buffer),
            Err(e) => Err(RecordError::Encode { topic: channel.topic, reason: e.to_string() }),
        };
        self.buffer = buffer;
        result
    }

    /// Writes a JSON message at `log_time` (ns).
    pub fn write_json(
        &mut self,
        channel: Channel,
        log_time: u64,
        value: &serde_json::Value,
    ) -> Result<(), RecordError> {
        let mut buffer = std::mem::take(&mut self.buffer);
        buffer.clear();
        let encoded = serde_json::to_writer(&mut buffer, value);
        let result = match encoded {
            Ok(()) => self.write_bytes(channel, log_time, &buffer),
            Err(e) => Err(RecordError::Encode { topic: channel.topic, reason: e.to_string() }),
        };
        self.buffer = buffer;
        result
    }

    fn write_bytes(&mut self, channel: Channel, log_time: u64, data: &[u8]) -> Result<(), RecordError> {
        let header =
            MessageHeader { channel_id: channel.id, sequence: self.sequence, log_time, publish_time: log_time };
        self.sequence = self.sequence.wrapping_add(1);
        self.with(|w| w.write_to_known_channel(&header, data))
    }

    /// Closes the current chunk and hands everything written so far to the operating system.
    pub fn end_frame(&mut self) -> Result<(), RecordError> {
        self.with(|w| w.flush())
    }

    /// Stores a file (the scene description) as an MCAP attachment.
    pub fn attach(&mut self, name: &str, media_type: &str, data: &[u8], log_time: u64) -> Result<(), RecordError> {
        self.with(|w| {
            w.attach(&Attachment {
                log_time,
                create_time: log_time,
                name: name.to_string(),
                media_type: media_type.to_string(),
                data: Cow::Borrowed(data),
            })
        })
    }

    /// Writes a Metadata record `name` with the key–value pairs `entries`.
    pub fn metadata(&mut self, name: &str, entries: BTreeMap<String, String>) -> Result<(), RecordError> {
        self.with(|w| w.write_metadata(&Metadata { name: name.to_string(), metadata: entries }))
    }

    /// Writes the summary section and footer, and flushes the file.
    pub fn finish(mut self) -> Result<(), RecordError> {
        self.with(|w| w.finish())?;
        let writer = self.writer.take().ok_or_else(|| self.failed_earlier())?;
        let mut inner = writer.into_inner();
        std::io::Write::flush(&mut inner)
            .map_err(|source| RecordError::Io { path: self.path.display().to_string(), source })?;
        Ok(())
    }
}
