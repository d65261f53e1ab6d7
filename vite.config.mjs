// Front end: web/ is the app root, public/ (incl. the wasm build in public/wasm/) is copied verbatim to dist/.
// No COOP/COEP headers on purpose: the module is single-threaded and must embed in pages without isolation.
// `--port` on the command line overrides the ports below (scripts/start.sh uses 5173 for preview).
import { defineConfig } from 'vite';

export default defineConfig({
  root: 'web',
  publicDir: '../public',
  build: {
    outDir: '../dist',
    emptyOutDir: true,
    target: 'es2022',            // top-level await in the app modules
    chunkSizeWarningLimit: 1024, // three.js alone is ~540 kB minified
  },
  server: { host: '127.0.0.1', port: 5173, strictPort: true },
  preview: { host: '127.0.0.1', port: 4173, strictPort: true },
});
