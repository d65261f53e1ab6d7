// Loading the WebAssembly core. The module is a classic (non-ES) MODULARIZE build that defines the
// global factory createAdasculptModule. By default both files are found next to this package's
// JavaScript with `new URL(..., import.meta.url)`, which bundlers (vite, rollup, webpack) follow:
// they copy adasculpt.js and adasculpt.wasm into the host's build and rewrite the URLs. A page
// that already has the script tag (index.html, for a download in parallel with the app) keeps it.
// `wasmUrl` points elsewhere (a CDN folder holding both files): the .wasm is then looked up next
// to that script.

const DEFAULT_SCRIPT = new URL('../public/wasm/adasculpt.js', import.meta.url).href;
const DEFAULT_WASM = new URL('../public/wasm/adasculpt.wasm', import.meta.url).href;

let factoryPromise = null;

function loadFactory(scriptUrl) {
  if (typeof globalThis.createAdasculptModule === 'function') {
    return Promise.resolve(globalThis.createAdasculptModule);
  }
  if (!factoryPromise) {
    factoryPromise = new Promise((resolve, reject) => {
      const existing = document.querySelector('script[data-adasculpt-wasm]');
      const script = existing || document.createElement('script');
      const done = () => {
        forget();
        if (typeof globalThis.createAdasculptModule === 'function') resolve(globalThis.createAdasculptModule);
        else reject(new Error(`${script.src} did not define createAdasculptModule`));
      };
      const failed = () => {
        forget();
        reject(new Error(`could not load ${script.src}`));
      };
      const forget = () => {
        script.removeEventListener('load', done);
        script.removeEventListener('error', failed);
      };
      script.addEventListener('load', done);
      script.addEventListener('error', failed);
      if (!existing) {
        script.src = scriptUrl;
        script.async = true;
        script.dataset.adasculptWasm = '';
        document.head.appendChild(script);
      }
    });
    factoryPromise.catch(() => { factoryPromise = null; });
  }
  return factoryPromise;
}

// A fresh module instance (each sculptor owns its own wasm memory; dropping it frees everything).
export async function instantiateCore(scriptUrl) {
  const url = scriptUrl ? new URL(scriptUrl, document.baseURI).href : DEFAULT_SCRIPT;
  const factory = await loadFactory(url);
  const wasm = scriptUrl ? new URL('adasculpt.wasm', url).href : DEFAULT_WASM;
  return factory({ locateFile: (file) => (file.endsWith('.wasm') ? wasm : file) });
}
