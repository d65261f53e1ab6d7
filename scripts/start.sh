#!/usr/bin/env bash
# Build everything and serve the production build of the web app (what `npm start` runs).
#   PORT=8080 npm start   to use another port (default 5173).
set -euo pipefail
cd "$(dirname "$0")/.."
PORT=${PORT:-5173}
bash scripts/setup.sh
bash scripts/build.sh native wasm
npx vite build --logLevel warn
echo
echo "adasculpt is being served at http://127.0.0.1:${PORT}/   (Ctrl-C to stop)"
echo "  examples: http://127.0.0.1:${PORT}/addon.html (AdaptiveSculptor in a three.js scene), /embed.html, /element.html"
echo
# Same as `npx vite preview ...`, but exec'ing vite itself means a SIGTERM to this script's pid stops the server
# (through npx, killing the npm process leaves vite running as an orphan).
exec ./node_modules/.bin/vite preview --port "$PORT" --host 127.0.0.1 --strictPort
