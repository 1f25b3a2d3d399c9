// Builds the live view's page: `node web/build.mjs OUT_DIR` writes exactly
//   OUT_DIR/index.html  the page
//   OUT_DIR/app.js      every module and dependency in one minified ES module (no requests out)
//   OUT_DIR/app.css     the page's CSS with uPlot's
// The output depends only on the sources and the locked dependencies (no dates, no hashes of
// paths), so two builds are byte for byte the same.
import { copyFile, mkdir, rm } from "node:fs/promises";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import * as esbuild from "esbuild";

const webDir = dirname(fileURLToPath(import.meta.url));

async function build(outDir) {
  await mkdir(outDir, { recursive: true });
  await esbuild.build({
    absWorkingDir: webDir,
    entryPoints: { app: "src/main.js" },  // app.js, and app.css from the CSS it imports
    outdir: outDir,
    bundle: true,
    format: "esm",
    platform: "browser",
    target: ["es2022", "chrome110", "firefox115", "safari16"],
    minify: true,
    sourcemap: false,
    legalComments: "none",
    charset: "utf8",
    logLevel: "warning",
  });
  await copyFile(join(webDir, "index.html"), join(outDir, "index.html"));
  await rm(join(outDir, "app.js.map"), { force: true });
}

const outDir = process.argv[2];
if (!outDir || process.argv.length > 3) {
  console.error("usage: node web/build.mjs OUT_DIR");
  process.exit(2);
}
build(resolve(outDir)).catch((error) => {
  console.error(error.message ?? error);
  process.exit(1);
});
