// SPDX-License-Identifier: Apache-2.0
// A Foxglove WebSocket client that subscribes to every channel a server
// advertises and counts what comes: the load of foxglove-cost.sh.
//   node subscribe-all.mjs WS_URL
import WebSocket from "ws";
import wsProtocol from "@foxglove/ws-protocol";

const { FoxgloveClient } = wsProtocol;
const client = new FoxgloveClient({ ws: new WebSocket(process.argv[2], [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
let messages = 0;
client.on("advertise", (channels) => channels.forEach((c) => client.subscribe(c.id)));
client.on("message", () => ++messages);
client.on("error", (e) => console.error(`subscribe-all: ${e}`));
setInterval(() => console.log(`messages ${messages}`), 5000);
