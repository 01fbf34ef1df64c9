// Reads every message of a wbv MCAP run with @mcap/core — the reader the Foxglove app and
// Lichtblick use to open local files — and checks it.
// Checks: McapIndexedReader (refuses chunks without message indexes) with CRC validation; every
// message JSON.parse-able into an object and valid (ajv) against its channel schema; channels whose
// schema is `foxglove.X` carry exactly the published @foxglove/schemas JSON schema and every message
// validates against it; counts equal the statistics; metadata and attachments readable; a second
// pass with McapStreamReader (validateCrcs) parses every record to the end.
// Usage: node validate.js FILE.mcap   (exit status 1 on any failure)
"use strict";
const fs = require("node:fs/promises");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { loadDecompressHandlers } = require("@mcap/support");
const foxglove = require("@foxglove/schemas/jsonschema");
const Ajv = require("ajv");
const { isDeepStrictEqual } = require("node:util");

async function main(path) {
  const problems = [];
  const fail = (m) => {
    if (problems.length < 20) console.error(`@mcap/core: ${path}: ${m}`);
    problems.push(m);
  };
  const decompressHandlers = await loadDecompressHandlers();
  const handle = await fs.open(path, "r");
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle),
      decompressHandlers,
    });
    const ajv = new Ajv({ strict: false, allErrors: false });
    const validators = new Map();
    for (const [id, ch] of reader.channelsById) {
      const schema = reader.schemasById.get(ch.schemaId);
      if (ch.messageEncoding !== "json") fail(`${ch.topic}: message encoding ${ch.messageEncoding}`);
      if (!schema || schema.encoding !== "jsonschema") {
        fail(`${ch.topic}: no jsonschema schema`);
        continue;
      }
      const doc = JSON.parse(new TextDecoder().decode(schema.data));
      const validators_ = [ajv.compile(doc)];
      if (schema.name.startsWith("foxglove.")) {
        const published = foxglove[schema.name.slice("foxglove.".length)];
        if (!published) fail(`${ch.topic}: ${schema.name} is not a published Foxglove schema`);
        else {
          if (!isDeepStrictEqual(doc, published))
            fail(`${ch.topic}: embedded ${schema.name} differs from @foxglove/schemas`);
          validators_.push(ajv.compile(published));
        }
      }
      validators.set(id, validators_);
    }
    const counts = new Map();
    for await (const m of reader.readMessages({ validateCrcs: true })) {
      counts.set(m.channelId, (counts.get(m.channelId) ?? 0) + 1);
      const ch = reader.channelsById.get(m.channelId);
      let obj;
      try {
        obj = JSON.parse(new TextDecoder().decode(m.data));
      } catch (e) {
        fail(`${ch.topic} #${m.sequence}: invalid JSON: ${e.message}`);
        continue;
      }
      if (obj === null || typeof obj !== "object" || Array.isArray(obj)) {
        fail(`${ch.topic} #${m.sequence}: not a JSON object`);
        continue;
      }
      for (const v of validators.get(m.channelId) ?? []) {
        if (!v(obj)) fail(`${ch.topic} #${m.sequence}: ${ajv.errorsText(v.errors)}`);
      }
    }
    const stats = reader.statistics;
    if (!stats) fail("no statistics record");
    else
      for (const [id, n] of stats.channelMessageCounts) {
        if ((counts.get(id) ?? 0) !== Number(n))
          fail(`channel ${id}: read ${counts.get(id) ?? 0} messages, statistics say ${n}`);
      }
    let metadata = 0;
    for await (const _ of reader.readMetadata()) metadata++;
    let attachments = 0;
    for await (const _ of reader.readAttachments()) attachments++;

    const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
    stream.append(await fs.readFile(path));
    let records = 0;
    for (let r; (r = stream.nextRecord()); ) records++;
    if (!stream.done()) fail("McapStreamReader did not reach the end of the file");

    const total = [...counts.values()].reduce((a, b) => a + b, 0);
    if (problems.length) {
      console.error(`@mcap/core: ${path}: FAILED (${problems.length} problems)`);
      return 1;
    }
    console.log(
      `@mcap/core ${path}: ok — ${total} messages on ${counts.size} channels, all schema-valid` +
        ` (foxglove.* against @foxglove/schemas); ${metadata} metadata, ${attachments} attachments,` +
        ` ${records} records streamed`,
    );
    return 0;
  } finally {
    await handle.close();
  }
}

if (process.argv.length !== 3) {
  console.error("usage: node validate.js FILE.mcap");
  process.exit(2);
}
main(process.argv[2]).then(
  (code) => process.exit(code),
  (e) => {
    console.error(`@mcap/core: ${process.argv[2]}: FAILED: ${e.message}`.split("\n")[0]);
    process.exit(1);
  },
);
