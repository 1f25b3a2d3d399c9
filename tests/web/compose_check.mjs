// docker/compose.yaml read by a YAML parser the project did not write, and checked for what runs N
// servers: flagd scaled by FLAGSIM_SERVERS with a prefix of its own each (--prefix auto), the
// recorder's channel pattern taking every such prefix, and the gateway serving every server heard
// (no --prefix). PREFIX is a prefix as `flagd --prefix auto` draws one. No Docker is needed.
//   node compose_check.mjs COMPOSE_YAML PREFIX
import { readFileSync } from "node:fs";

import { parse } from "yaml";

import { check, run, section } from "./checks.mjs";

const [composeFile, randomPrefix] = process.argv.slice(2);

/// The value after `option` in a command list.
const after = (command, option) => command[command.indexOf(option) + 1];

await run(async () => {
  section(`the services in ${composeFile}`);
  const { services } = parse(readFileSync(composeFile, "utf8"));
  check("flagd, a recorder and a gateway", ["flagd", "recorder", "gateway"].every((name) => services?.[name]),
        Object.keys(services ?? {}));
  const flagd = services.flagd;
  check("  flagd: as many replicas as FLAGSIM_SERVERS says, one by default",
        flagd.deploy?.replicas === "${FLAGSIM_SERVERS:-1}", flagd.deploy);
  check("  each with a prefix of its own unless FLAGSIM_PREFIX fixes one",
        after(flagd.command, "--prefix") === "${FLAGSIM_PREFIX:-auto}", flagd.command);
  const pattern = after(services.recorder.command, "-c");
  const whole = new RegExp(`^(?:${pattern})$`);
  check(`  the recorder's channels (${pattern}) take a drawn prefix's and the default's`,
        whole.test(`${randomPrefix}STATUS`) && whole.test("FLAGSIM_TILE"), randomPrefix);
  const gateway = services.gateway.command;
  check("  the gateway serves every server heard: flagctl serve without --prefix",
        gateway[0] === "flagctl" && gateway[1] === "serve" && !gateway.includes("--prefix"), gateway);
  check("  all on the host's network (multicast)",
        Object.values(services).every((service) => service.network_mode === "host"));
});
