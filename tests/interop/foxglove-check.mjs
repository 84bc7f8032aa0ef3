// SPDX-License-Identifier: Apache-2.0
// `flatsat foxglove` on a live paced rig, as Foxglove sees it: the published
// client (@foxglove/ws-protocol over ws) and OMG IDL CDR reader
// (@foxglove/omgidl-parser, @foxglove/omgidl-serialization), none written here.
//   node foxglove-check.mjs WS_URL RUN_DIR BRIDGE_PID
// 1. serverInfo and advertisements: every channel omgidl + cdr; subscribe to all;
//    then the CPU the bridge and the rig use over 10 s of that (cpu-window.sh).
// 2. at least 50 samples each of flatsat/gyro and flatsat/truth decoded with
//    the advertised schema: every number finite, steps rising, timestamps the
//    samples' simulated time.
// 3. malformed client messages get an error status and the stream goes on.
// 4. client publish: a detumble command accepted by the unloading controller;
//    a mode out of range and a non-command topic refused with a reason.
// 5. health: a component halted past its health lease is an error status, and
//    information again once it goes on; the run's end is information
//    (stopped), never an error.
import { execSync } from "node:child_process";
import { fileURLToPath } from "node:url";
import WebSocket from "ws";
import wsProtocol from "@foxglove/ws-protocol";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader, MessageWriter } from "@foxglove/omgidl-serialization";

const { FoxgloveClient } = wsProtocol;
const [url, runDir, bridgePid] = process.argv.slice(2);
const failures = [];
function check(ok, what) {
  if (!ok) failures.push(what);
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
async function until(condition, seconds, what) {
  const end = Date.now() + seconds * 1000;
  while (!condition()) {
    if (Date.now() > end) {
      check(false, `${what} (waited ${seconds} s)`);
      return false;
    }
    await sleep(50);
  }
  return true;
}

const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
let serverInfo = null;
const channels = new Map(); // channel id -> channel
const bySubscription = new Map(); // subscription id -> { channel, reader }
const received = new Map(); // topic -> [{ timestamp, message }]
const statuses = [];
client.on("error", (e) => check(false, `client error: ${e}`));
client.on("serverInfo", (info) => (serverInfo = info));
client.on("status", (s) => statuses.push({ ...s, at: Date.now() }));
client.on("advertise", (list) => {
  for (const channel of list) {
    channels.set(channel.id, channel);
    check(channel.encoding === "cdr" && channel.schemaEncoding === "omgidl", `${channel.topic}: cdr with an omgidl schema`);
    const reader = new MessageReader(channel.schemaName, parseIDL(channel.schema));
    bySubscription.set(client.subscribe(channel.id), { channel, reader });
  }
});
let messagesAfter = 0;
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const { channel, reader } = bySubscription.get(subscriptionId);
  ++messagesAfter;
  if (channel.topic !== "flatsat/gyro" && channel.topic !== "flatsat/truth") return;
  const list = received.get(channel.topic) ?? [];
  list.push({ timestamp, message: reader.readMessage(data) });
  received.set(channel.topic, list);
});

await until(() => serverInfo !== null, 20, "serverInfo");
check(serverInfo?.capabilities.includes("clientPublish"), "serverInfo offers clientPublish");
check(serverInfo?.supportedEncodings?.includes("cdr"), "serverInfo: cdr");
await until(() => ["flatsat/gyro", "flatsat/truth"].every((t) => (received.get(t)?.length ?? 0) >= 50), 60,
            "50 samples each of flatsat/gyro and flatsat/truth");

// What watching everything costs: the bridge's CPU beside the rig's, in steady state.
const cpuWindow = fileURLToPath(new URL("./cpu-window.sh", import.meta.url));
console.log(`watching every channel: ${execSync(`bash ${cpuWindow} ${runDir} 10 ${bridgePid}`).toString().trim()}`);

// 2. Decoded samples: finite numbers, steps rising, stamped with simulated time.
function numbers(value, out = []) {
  if (typeof value === "number") out.push(value);
  else if (typeof value === "bigint") out.push(Number(value));
  else if (value && typeof value === "object") for (const v of Object.values(value)) numbers(v, out);
  return out;
}
for (const topic of ["flatsat/gyro", "flatsat/truth"]) {
  const list = received.get(topic) ?? [];
  list.forEach(({ timestamp, message }, i) => {
    check(numbers(message).every(Number.isFinite), `${topic}#${i}: every number finite`);
    check(timestamp === BigInt(message.header.sim_time_ns), `${topic}#${i}: timestamp is the sample's simulated time`);
    if (i > 0) {
      check(BigInt(message.header.step) > BigInt(list[i - 1].message.header.step), `${topic}#${i}: steps rise`);
    }
  });
  console.log(`${topic}: ${list.length} samples decoded, steps ${list[0]?.message.header.step}..${list.at(-1)?.message.header.step}`);
}

// 3. Malformed client messages: an error status each, and the bridge goes on.
const errorsBefore = statuses.filter((s) => s.level === 2).length;
ws.send("{not json");
ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 999, channelId: 99999 }] }));
ws.send(JSON.stringify({ op: "teleport" }));
ws.send(Buffer.from([7, 1, 2]));
await until(() => statuses.filter((s) => s.level === 2).length >= errorsBefore + 4, 10, "four error statuses");
const malformed = statuses.filter((s) => s.level === 2).slice(errorsBefore).map((s) => s.message);
check(malformed.some((m) => m.includes("not JSON")), "bad JSON named");
check(malformed.some((m) => m.includes("channel 99999 is not advertised")), "unknown channel named");
check(malformed.some((m) => m.includes("'teleport' is not supported")), "unknown op named");
check(malformed.some((m) => m.includes("binary opcode 7")), "unknown binary opcode named");
const countAfter = messagesAfter;
await until(() => messagesAfter > countAfter + 20, 10, "samples still streaming after malformed messages");

// 4. Client publish: the operator's mode command, checked and acknowledged.
const modeChannel = [...channels.values()].find((c) => c.topic === "flatsat/unloading_mode_cmd");
check(modeChannel !== undefined, "flatsat/unloading_mode_cmd advertised for publishing");
if (modeChannel) {
  const writer = new MessageWriter(modeChannel.schemaName, parseIDL(modeChannel.schema));
  const modeCmd = (mode) => ({
    header: { step: 0n, sim_time_ns: 0n, sample_time_ns: 0n, source: Array.from({ length: 32 }, () => 0) },
    command_id: 0n,
    mode,
  });
  const published = client.advertise({ topic: modeChannel.topic, encoding: "cdr", schemaName: modeChannel.schemaName });
  client.sendMessage(published, writer.writeMessage(modeCmd(1))); // MAGNETIC_DETUMBLE
  await until(() => statuses.some((s) => /accepted by unloading_controller/.test(s.message)), 20,
              "the detumble command acknowledged by the unloading controller");
  client.sendMessage(published, writer.writeMessage(modeCmd(7)));
  await until(() => statuses.some((s) => s.level === 2 && s.message.includes("mode 7 is none of")), 10,
              "mode 7 refused before it was sent");
}
const truth = [...channels.values()].find((c) => c.topic === "flatsat/truth");
client.advertise({ topic: truth.topic, encoding: "cdr", schemaName: truth.schemaName });
await until(() => statuses.some((s) => s.level === 2 && s.message.includes("clients publish only the operator commands")),
            10, "publishing on flatsat/truth refused");

// 5. Health: a halted component is an error until it goes on; the run's end is information.
check(statuses.some((s) => s.level === 0 && / RUNNING/.test(s.message)), "running components reported as information");
// SIGSTOP for longer than the health lease (3 s): lost, an error; then back.
const sunSensor = `'flatsat-sun_senso[r] --scenario ${runDir}/'`;
execSync(`pkill -STOP -f ${sunSensor}`);
await until(() => statuses.some((s) => s.level === 2 && /^sun_sensor lost while RUNNING/.test(s.message)), 15,
            "the halted sun sensor reported lost, as an error");
const lostAt = statuses.findIndex((s) => /^sun_sensor lost/.test(s.message));
await sleep(1000);
check(!statuses.slice(lostAt).some((s) => /^sun_sensor RUNNING/.test(s.message)),
      "the halted sun sensor not reported RUNNING while halted");
execSync(`pkill -CONT -f ${sunSensor}`);
await until(() => statuses.slice(lostAt).some((s) => s.level === 0 && /^sun_sensor RUNNING/.test(s.message)), 15,
            "the sun sensor reported RUNNING again once it went on");
await until(() => statuses.some((s) => /^dynamics_server stopped/.test(s.message)), 90, "the run's end reported");
await sleep(4000); // the others' participants leave
const ending = statuses.filter((s) => /stopped/.test(s.message) || /STOPPED/.test(s.message));
check(ending.length > 3, `the run's end reported for the components (${ending.length} statuses)`);
check(ending.every((s) => s.level === 0), "a completed run is information, not an error");
const alarms = statuses.filter((s) => s.level === 2 && / lost while | FAILED/.test(s.message) && !s.message.startsWith("sun_sensor"));
check(alarms.length === 0, `no other component in alarm: ${alarms.map((s) => s.message).join("; ")}`);
client.close();

console.log(`statuses received: ${statuses.length}; samples received: ${messagesAfter}`);
if (failures.length > 0) for (const s of statuses) console.log(`  status ${s.level} at +${((s.at - statuses[0].at) / 1000).toFixed(1)} s: ${s.message}`);
if (failures.length > 0) {
  console.error(`FAILED ${failures.length} checks:\n  ${[...new Set(failures)].slice(0, 30).join("\n  ")}`);
  process.exit(1);
}
console.log("foxglove interop: every check passed");
