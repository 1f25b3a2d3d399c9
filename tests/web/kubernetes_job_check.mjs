// The Kubernetes Indexed Job scripts/sweep writes (--engine kubernetes), read as YAML by a YAML
// parser the project did not write, and checked for what a cluster needs of it: one pod per task,
// each given its index, the task script of the sweep, the sweep's folder mounted where the script
// looks for it. No cluster is needed for that.
//   node kubernetes_job_check.mjs JOB_YAML SWEEP_DIR TASKS THROTTLE
import { readFileSync } from "node:fs";

import { parse } from "yaml";

import { check, run, section } from "./checks.mjs";

const [jobFile, sweepDir, tasks, throttle] = process.argv.slice(2);

await run(async () => {
  section(`the Indexed Job in ${jobFile}`);
  const job = parse(readFileSync(jobFile, "utf8"));
  check("it is a batch/v1 Job", job.apiVersion === "batch/v1" && job.kind === "Job", `${job.apiVersion} ${job.kind}`);
  const spec = job.spec ?? {};
  check("  Indexed, one completion per task", spec.completionMode === "Indexed" && spec.completions === Number(tasks),
        `${spec.completionMode} ${spec.completions}`);
  check(`  at most ${throttle} pods at once`, spec.parallelism === Number(throttle), spec.parallelism);
  const pod = spec.template?.spec ?? {};
  check("  pods are not restarted in place (a failed index is retried by the Job)", pod.restartPolicy === "Never", pod.restartPolicy);
  const container = pod.containers?.[0] ?? {};
  check("  each runs the sweep's task script", JSON.stringify(container.command) === JSON.stringify([`${sweepDir}/task.sh`]),
        container.command);
  const mount = container.volumeMounts?.[0] ?? {};
  const volume = (pod.volumes ?? []).find((v) => v.name === mount.name);
  check("  with the sweep's folder mounted where the script looks, from a claim every node can mount",
        mount.mountPath === sweepDir && Boolean(volume?.persistentVolumeClaim?.claimName), { mount, volume });
  const script = readFileSync(`${sweepDir}/task.sh`, "utf8");
  check("  and the task script takes its index from JOB_COMPLETION_INDEX", script.includes("JOB_COMPLETION_INDEX"));
});
