// SPDX-License-Identifier: Apache-2.0
// A Foxglove client that subscribes to every channel `flatsat foxglove`
// advertises and counts what arrives, for SECONDS; the load of the bridge
// figure (foxglove-check.sh).   node foxglove-subscribe-all.mjs WS_URL SECONDS
import WebSocket from "ws";
import wsProtocol from "@foxglove/ws-protocol";

const { FoxgloveClient } = wsProtocol;
const [url, seconds] = process.argv.slice(2);
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
let messages = 0;
let bytes = 0;
client.on("advertise", (channels) => channels.forEach((c) => client.subscribe(c.id)));
client.on("message", ({ data }) => {
  ++messages;
  bytes += data.byteLength;
});
setTimeout(() => {
  console.log(`subscriber: ${messages} messages, ${bytes} bytes in ${seconds} s`);
  client.close();
}, Number(seconds) * 1000);
