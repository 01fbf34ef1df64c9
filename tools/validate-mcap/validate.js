// Reads every message of a wbv MCAP run with @mcap/core — the reader the Foxglove app and
// Lichtblick use to open local files — and checks it.
// Checks: McapIndexedReader (refuses chunks without message indexes) with CRC validation; every
// message JSON.parse-able into an object and valid (ajv) against its channel schema; channels whose
// schema is `foxglove.X` carry exactly the published @foxglove/schemas JSON schema and every message
// validates against it; counts equal the statistics; metadata and attachments readable; a second
// pass with McapStreamReader (validateCrcs) parses every record to the end.
// Protobuf channels (the default): schema encoding `protobuf` with a fully qualified name and a
// FileDescriptorSet, loaded with protobufjs (its own descriptor reader); every message decoded and
// re-checked (every double finite; a decoded message round-trips through protobufjs); `foxglove.*`
// schemas compared field by field (name, number, type, label) with the `.proto` that
// @foxglove/schemas' own generator (`generateProto`) writes for the published schema.
// Layout: every plot path of the Foxglove/Lichtblick layout that travels with the run
// (`wbv-layout.json` beside the file, else tools/viewer/wbv-layout.json) must resolve, on a
// per-sample run, to a full-rate series: a finite number in every message of its topic (decoded
// with protobufjs, the decoder the Foxglove app uses for protobuf, or JSON.parse), log times one
// sample period (`wbv.run` sample_rate_hz) apart. Neither Foxglove nor Lichtblick publishes its
// message-path parser to npm, so the paths are split here: `/topic.field.sub` (no filters or
// slices, which the layout does not use).
// Usage: node validate.js FILE.mcap   (exit status 1 on any failure)
"use strict";
const fs = require("node:fs/promises");
const nodePath = require("node:path");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { loadDecompressHandlers } = require("@mcap/support");
const foxglove = require("@foxglove/schemas/jsonschema");
const Ajv = require("ajv");
const { isDeepStrictEqual } = require("node:util");
const protobuf = require("protobufjs");
const descriptor = require("protobufjs/ext/descriptor");
const internal = require("@foxglove/schemas/internal");

// The published Foxglove schemas as protobufjs types, from @foxglove/schemas' generated `.proto`.
function publishedFoxglove() {
  const root = new protobuf.Root();
  const enums = Object.values(internal.foxgloveEnumSchemas);
  for (const schema of Object.values(internal.foxgloveMessageSchemas)) {
    const nested = enums.filter((e) => e.parentSchemaName === schema.name);
    const text = internal.generateProto(schema, nested);
    protobuf.parse(text, root); // camelCase names, as Root.fromDescriptor gives them
  }
  // google.protobuf.Timestamp / Duration, imported by the generated files
  protobuf.parse(
    `syntax = "proto3"; package google.protobuf;
     message Timestamp { int64 seconds = 1; int32 nanos = 2; }
     message Duration { int64 seconds = 1; int32 nanos = 2; }`,
    root,
  );
  root.resolveAll();
  return root;
}

// Field-by-field difference of two protobufjs message types and the types they use.
function compareTypes(ours, theirs, at, seen, fail) {
  if (seen.has(at)) return;
  seen.add(at);
  const names = new Set([...Object.keys(ours.fields), ...Object.keys(theirs.fields)]);
  for (const n of names) {
    const a = ours.fields[n];
    const b = theirs.fields[n];
    if (!a || !b) {
      fail(`${at}.${n}: ${a ? "not in" : "missing from the file, but in"} @foxglove/schemas`);
      continue;
    }
    const ta = a.resolvedType ? a.resolvedType.fullName : a.type;
    const tb = b.resolvedType ? b.resolvedType.fullName : b.type;
    if (a.id !== b.id || ta !== tb || a.repeated !== b.repeated)
      fail(`${at}.${n}: ${a.id} ${ta}${a.repeated ? "[]" : ""} vs published ${b.id} ${tb}${b.repeated ? "[]" : ""}`);
    else if (a.resolvedType instanceof protobuf.Type)
      compareTypes(a.resolvedType, b.resolvedType, ta.replace(/^\./, ""), seen, fail);
  }
}

function finiteDoubles(type, msg, at, fail) {
  for (const f of type.fieldsArray) {
    const v = msg[f.name];
    if (v === undefined || v === null) continue;
    const values = f.repeated ? v : [v];
    for (const x of values) {
      if (f.type === "double" && !Number.isFinite(x)) fail(`${at}.${f.name}: not finite`);
      if (f.resolvedType instanceof protobuf.Type) finiteDoubles(f.resolvedType, x, `${at}.${f.name}`, fail);
    }
  }
}

// The plot paths of a Foxglove/Lichtblick layout: [{panel, path}] of every enabled series.
function layoutPlotPaths(layout) {
  const out = [];
  for (const [panel, config] of Object.entries(layout.configById ?? {})) {
    if (!panel.startsWith("Plot!")) continue;
    for (const p of config.paths ?? []) if (p.enabled !== false) out.push({ panel, path: p.value });
  }
  return out;
}

// The layout that travels with `path`, with its file name.
async function runLayout(path) {
  const beside = nodePath.join(nodePath.dirname(path), "wbv-layout.json");
  const shipped = nodePath.join(__dirname, "..", "viewer", "wbv-layout.json");
  for (const f of [beside, shipped]) {
    try {
      return { file: f, layout: JSON.parse(await fs.readFile(f, "utf8")) };
    } catch (e) {
      if (e.code !== "ENOENT") throw e;
    }
  }
  throw new Error("no wbv-layout.json beside the file or in tools/viewer");
}

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
    const types = new Map();
    const namedTypes = new Map();
    let published;
    for (const [id, ch] of reader.channelsById) {
      const schema = reader.schemasById.get(ch.schemaId);
      if (ch.messageEncoding === "protobuf") {
        if (!schema || schema.encoding !== "protobuf") {
          fail(`${ch.topic}: protobuf channel without a protobuf schema`);
          continue;
        }
        if (!/^[A-Za-z_][\w]*(\.[A-Za-z_][\w]*)+$/.test(schema.name))
          fail(`${ch.topic}: schema name ${schema.name} is not fully qualified`);
        const fds = descriptor.FileDescriptorSet.decode(schema.data);
        const root = protobuf.Root.fromDescriptor(fds);
        root.resolveAll();
        const type = root.lookupType(schema.name);
        types.set(id, type);
        // With the names of the .proto (`a_seat_z`), as the Foxglove app and Lichtblick show them.
        const named = protobuf.Root.fromDescriptor(fds, { keepCase: true });
        named.resolveAll();
        namedTypes.set(id, named.lookupType(schema.name));
        if (schema.name.startsWith("foxglove.")) {
          published ??= publishedFoxglove();
          compareTypes(type, published.lookupType(schema.name), schema.name, new Set(), fail);
        }
        continue;
      }
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
    const { file: layoutFile, layout } = await runLayout(path);
    // Per plot path: the topic, the field names, and the series read (points, last log time).
    const plots = layoutPlotPaths(layout).map(({ panel, path: p }) => {
      const dot = p.indexOf(".");
      return { panel, path: p, topic: p.slice(0, dot), fields: p.slice(dot + 1).split("."), points: 0, bad: 0, gaps: 0, last: null };
    });
    let period = null;
    for await (const m of reader.readMetadata({ name: "wbv.run" })) {
      const hz = Number(m.metadata.get("sample_rate_hz"));
      if (hz > 0) period = BigInt(Math.round(1e9 / hz));
    }
    const series = (topic, msg, logTime) => {
      for (const s of plots) {
        if (s.topic !== topic) continue;
        let v = msg;
        for (const f of s.fields) v = v === undefined || v === null ? undefined : v[f];
        if (typeof v !== "number" || !Number.isFinite(v)) s.bad++;
        else s.points++;
        if (s.last !== null && period !== null && logTime - s.last !== period) s.gaps++;
        s.last = logTime;
      }
    };
    const counts = new Map();
    for await (const m of reader.readMessages({ validateCrcs: true })) {
      counts.set(m.channelId, (counts.get(m.channelId) ?? 0) + 1);
      const ch = reader.channelsById.get(m.channelId);
      const type = types.get(m.channelId);
      if (type) {
        let msg;
        try {
          msg = type.decode(m.data);
        } catch (e) {
          fail(`${ch.topic} #${m.sequence}: protobuf decode: ${e.message}`);
          continue;
        }
        if (plots.some((p) => p.topic === ch.topic)) series(ch.topic, namedTypes.get(m.channelId).decode(m.data), m.logTime);
        finiteDoubles(type, msg, `${ch.topic} #${m.sequence}`, fail);
        // Re-encoded (protobufjs writes field-number order), it decodes to the same message.
        const again = type.decode(type.encode(msg).finish());
        if (!isDeepStrictEqual(type.toObject(again), type.toObject(msg)))
          fail(`${ch.topic} #${m.sequence}: does not round-trip through protobufjs`);
        continue;
      }
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
      series(ch.topic, obj, m.logTime);
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
    // A batched run (`--layout batched`) holds arrays: the layout's paths are for per-sample runs.
    const batched = [...reader.schemasById.values()].some((s) => s.name.endsWith("Batch"));
    let layoutNote;
    if (batched) layoutNote = `layout ${layoutFile}: not checked (batched run: the plot paths are for per-sample runs)`;
    else {
      for (const s of plots) {
        const topic = [...reader.channelsById].find(([, c]) => c.topic === s.topic);
        const n = topic ? counts.get(topic[0]) ?? 0 : 0;
        if (!topic) fail(`layout ${s.panel} ${s.path}: no topic ${s.topic}`);
        else if (s.bad || s.points !== n || n < 2)
          fail(`layout ${s.panel} ${s.path}: ${s.points} numbers in ${n} messages (${s.bad} without a finite number)`);
        else if (period === null || s.gaps)
          fail(`layout ${s.panel} ${s.path}: ${s.gaps} steps other than the sample period ${period} ns`);
      }
      const points = [...new Set(plots.map((s) => s.points))].join("/");
      layoutNote = `layout ${nodePath.basename(layoutFile)}: ${plots.length} plot paths resolve to series at the sample rate (${points} points, ${period} ns apart)`;
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
      `@mcap/core ${path}: ok — ${total} messages on ${counts.size} channels, all decoded and` +
        ` schema-valid (foxglove.* against @foxglove/schemas); ${metadata} metadata, ${attachments} attachments,` +
        ` ${records} records streamed; ${layoutNote}`,
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
