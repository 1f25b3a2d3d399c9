// An MCAP file as Foxglove's own reader (@mcap/core) reads it: streamed record by record with
// every CRC checked, and through its summary and index as a viewer seeks in it. Every message
// must decode: JSON that holds its schema's required fields with their types; /flag/image a JPEG.
// Usage: node mcap_check.mjs FILE.mcap TOPIC... (the topics that must hold messages)
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { open, readFile } from "node:fs/promises";
import { check, run } from "./checks.mjs";

const [file, ...wanted] = process.argv.slice(2);
const decoder = new TextDecoder();

const kTypes = {
  number: (v) => typeof v === "number", integer: (v) => Number.isInteger(v), string: (v) => typeof v === "string",
  boolean: (v) => typeof v === "boolean", object: (v) => v !== null && typeof v === "object" && !Array.isArray(v),
  array: (v) => Array.isArray(v),
};

/// "" if `message` holds `schema`'s required fields and its properties' types (top level), else what does not.
function schemaProblem(schema, message) {
  if (!kTypes.object(message)) return "not a JSON object";
  for (const name of schema.required ?? []) if (!(name in message)) return `no ${name}`;
  for (const [name, property] of Object.entries(schema.properties ?? {})) {
    if (!(name in message) || !property.type) continue;
    const types = [property.type].flat();
    if (!types.some((type) => kTypes[type]?.(message[name]))) return `${name}: not ${types.join(" or ")}`;
  }
  return "";
}

/// The messages of the file, read through the summary and the chunk index.
async function indexedMessages() {
  const handle = await open(file, "r");
  const readable = {
    size: async () => BigInt((await handle.stat()).size),
    read: async (offset, length) => {
      const buffer = new Uint8Array(Number(length));
      await handle.read(buffer, 0, Number(length), Number(offset));
      return buffer;
    },
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const messages = [];
  for await (const message of reader.readMessages()) messages.push(message);
  await handle.close();
  return { reader, messages };
}

await run(async () => {
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(await readFile(file));
  const kinds = {};
  let streamedMessages = 0;
  for (let record; (record = stream.nextRecord());) {
    kinds[record.type] = (kinds[record.type] ?? 0) + 1;
    if (record.type === "Message") streamedMessages += 1;
  }
  check("streamed whole, every CRC checked (chunks, data section, summary)", stream.done(), kinds);

  const { reader, messages } = await indexedMessages();
  check("its summary and index lead to the same messages", messages.length === streamedMessages && messages.length > 0,
        `${messages.length} indexed, ${streamedMessages} streamed`);
  check("  and its statistics count them", Number(reader.statistics?.messageCount) === messages.length);
  const problems = [];
  const perTopic = {};
  let lastTime = 0n;
  for (const message of messages) {
    const channel = reader.channelsById.get(message.channelId);
    const schema = reader.schemasById.get(channel.schemaId);
    perTopic[channel.topic] = (perTopic[channel.topic] ?? 0) + 1;
    if (message.logTime < lastTime) problems.push(`${channel.topic}: out of time order`);
    lastTime = message.logTime;
    let json;
    try {
      json = JSON.parse(decoder.decode(message.data));
    } catch (error) {
      problems.push(`${channel.topic}: not JSON (${error.message})`);
      continue;
    }
    const problem = schemaProblem(JSON.parse(decoder.decode(schema.data)), json);
    if (problem) problems.push(`${channel.topic} (${schema.name}): ${problem}`);
    if (channel.topic === "/flag/image") {
      const jpeg = Buffer.from(json.data, "base64");
      if (json.format !== "jpeg" || jpeg[0] !== 0xff || jpeg[1] !== 0xd8) problems.push("/flag/image: not a JPEG");
    }
  }
  check(`every message decodes with its schema (${messages.length})`, problems.length === 0, problems.slice(0, 5));
  for (const topic of wanted) check(`  ${topic} holds messages (${perTopic[topic] ?? 0})`, (perTopic[topic] ?? 0) > 0, perTopic);
});
