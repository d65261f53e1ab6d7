// `npm pack` / `npm publish` run this first (package.json "prepack"): the package carries the wasm
// build next to its JavaScript, so refuse to pack without it.
import fs from 'node:fs';

const missing = ['public/wasm/adasculpt.js', 'public/wasm/adasculpt.wasm'].filter((f) => !fs.existsSync(f));
if (missing.length) {
  console.error(`npm pack: ${missing.join(', ')} missing; build them first: bash scripts/build.sh wasm`);
  process.exit(1);
}
