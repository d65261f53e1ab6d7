// Loading the WebAssembly core. The module is a classic (non-ES) MODULARIZE build that defines
// the global factory createAdasculptModule; it finds adasculpt.wasm next to its own script URL.
// index.html includes the script tag itself (so it downloads in parallel with the app); a host
// page that only imports app.js gets the tag injected here, once.

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
        if (typeof globalThis.createAdasculptModule === 'function') resolve(globalThis.createAdasculptModule);
        else reject(new Error(`${script.src} did not define createAdasculptModule`));
      };
      script.addEventListener('load', done, { once: true });
      script.addEventListener('error', () => reject(new Error(`could not load ${script.src}`)), { once: true });
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

// A fresh module instance (each app owns its own wasm memory; dropping it frees everything).
export async function instantiateCore(scriptUrl) {
  const url = scriptUrl || new URL('wasm/adasculpt.js', document.baseURI).href;
  const factory = await loadFactory(url);
  return factory({});
}
