// Front end: web/ is the app root, public/ (incl. the wasm build in public/wasm/) is copied verbatim to dist/.
// No COOP/COEP headers on purpose: the module is single-threaded and must embed in pages without isolation.
// ADASCULPT_DIST=../dist-me builds to (and `vite preview` serves) another folder, so several people can run e2e
// in one checkout. `--port` on the command line overrides the ports below (scripts/start.sh uses 5173 for preview).
// Every page in web/ is listed as an input, so the production build has /embed.html, /element.html and
// /addon.html next to /index.html (the dev server serves any page in web/ without this list).
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const page = (name) => fileURLToPath(new URL(`web/${name}`, import.meta.url));

export default defineConfig({
  root: 'web',
  publicDir: '../public',
  build: {
    outDir: process.env.ADASCULPT_DIST || '../dist',
    emptyOutDir: true,
    target: 'es2022',            // top-level await in the app modules
    chunkSizeWarningLimit: 1024, // three.js alone is ~540 kB minified
    rollupOptions: {
      input: {
        index: page('index.html'), embed: page('embed.html'), element: page('element.html'), addon: page('addon.html'),
      },
    },
  },
  server: { host: '127.0.0.1', port: 5173, strictPort: true },
  preview: { host: '127.0.0.1', port: 4173, strictPort: true },
});
