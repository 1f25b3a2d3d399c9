import assert from "node:assert/strict";
import { test } from "node:test";
import { kAliveWithin, kRestartShown, ServerWatch } from "../src/server_watch.js";

function watchOnAClock() {
  const clock = { ms: 0 };
  const restarts = [];
  const watch = new ServerWatch({ now: () => clock.ms, onRestart: (id, old) => restarts.push([id, old]) });
  return { clock, restarts, watch };
}

test("a server is alive while STATUS keeps coming, and gone when it stops", () => {
  const { clock, watch } = watchOnAClock();
  assert.equal(watch.state(), "waiting");
  watch.onStatus({ server_id: "17" });
  assert.equal(watch.state(), "alive");
  clock.ms += kAliveWithin - 1;
  assert.equal(watch.state(), "alive");
  clock.ms += 2;
  assert.equal(watch.state(), "gone");
  clock.ms = 7000;
  assert.match(watch.describe(), /server gone: no STATUS for 7 s/);
  watch.onStatus({ server_id: "17" });
  assert.equal(watch.state(), "alive", "the same server back (a pause in STATUS) is no restart");
});

test("a new server id is a restart, said for a while, then alive", () => {
  const { clock, restarts, watch } = watchOnAClock();
  watch.onStatus({ server_id: "17" });
  clock.ms += 3000;
  watch.onStatus({ server_id: "9007199254740993" });
  assert.deepEqual(restarts, [["9007199254740993", "17"]]);
  assert.equal(watch.state(), "restarted");
  clock.ms += kRestartShown - 1000;
  watch.onStatus({ server_id: "9007199254740993" });
  assert.equal(watch.state(), "restarted");
  clock.ms += 1000;
  watch.onStatus({ server_id: "9007199254740993" });
  assert.equal(watch.state(), "alive");
  assert.equal(restarts.length, 1);
});

test("without the gateway nothing is known of the server", () => {
  const { watch } = watchOnAClock();
  watch.onStatus({ server_id: "17" });
  watch.onDisconnect();
  assert.equal(watch.state(), "gone");
  assert.equal(watch.describe(), "server not heard");
});
