// <adasculpt-viewer>: the sculpting app as a custom element, for host pages that prefer markup.
//
//   <script type="module">import 'adasculpt/element';</script>
//   <adasculpt-viewer src="models/bunny.obj" epsilon="0.05%" style="height: 400px"></adasculpt-viewer>
//
// Attributes (all optional; changing one later applies it to the running app):
//   src            model URL (load)                        ui          "off": no panel, stats or help line
//   epsilon, min-length, max-length   number = absolute, "x%" = percent of the bounding-box diagonal
//   features       dihedral angle in degrees, 0 = off      wasm-url    URL of adasculpt.js (restarts the app)
//   handle-radius, roi-radius          grab radii, same units as the lengths
//   autosave       a key: autosave to IndexedDB under it and offer to restore (absent: no autosave;
//                  empty: the key 'viewer')
// The element is a block (400 px high unless the page sizes it) and the app follows its size.
// `element.app` is the page API (web/adasculpt.d.ts) once the `adasculpt-ready` event has fired;
// `adasculpt-error` carries {detail: Error} for a failed start, load or parameter. Removing the
// element from the page disposes the app (wasm instance, GPU resources, listeners).
import { createSculptApp } from './app.js';
import { lengthFromText } from './settings.js';

const PARAMS = {
  epsilon: 'epsilon', 'min-length': 'minLength', 'max-length': 'maxLength', features: 'features',
  'handle-radius': 'handleRadius', 'roi-radius': 'roiRadius',
};
const RESTART = ['ui', 'wasm-url', 'autosave'];

// Zero specificity: any rule of the host page wins.
const ELEMENT_STYLE = ':where(adasculpt-viewer) { display: block; position: relative; height: 400px; }';

function paramValue(name, text) {
  return name === 'features' ? Number(String(text).trim()) : lengthFromText(text);
}

export class AdasculptViewerElement extends HTMLElement {
  static observedAttributes = ['src', ...Object.keys(PARAMS), ...RESTART];

  #app = null;
  #generation = 0; // bumped by every stop: a start that finishes late disposes its own app

  get app() { return this.#app; }

  connectedCallback() {
    ensureStyle(this.ownerDocument);
    if (!this.#app) this.#start();
  }

  disconnectedCallback() {
    this.#stop();
  }

  attributeChangedCallback(name, oldValue, value) {
    const app = this.#app;
    if (!app || oldValue === value) return;
    if (RESTART.includes(name)) {
      this.#stop();
      this.#start();
    } else if (name === 'src') {
      // A load resets the core's settings to its defaults: the attributes apply again.
      if (value) app.load(value).then(() => this.#applyParams(), (e) => this.#fail(e));
    } else if (value !== null) {
      this.#setParams({ [PARAMS[name]]: paramValue(name, value) });
    }
  }

  async #start() {
    const generation = ++this.#generation;
    let app;
    try {
      app = await createSculptApp(this, {
        model: this.getAttribute('src') || null,
        ui: this.getAttribute('ui') !== 'off',
        ...(this.hasAttribute('wasm-url') ? { wasmUrl: this.getAttribute('wasm-url') } : {}),
        ...(this.hasAttribute('autosave') ? { autosave: this.getAttribute('autosave') || 'viewer' } : {}),
      });
    } catch (e) {
      if (generation === this.#generation) this.#fail(e);
      return;
    }
    if (generation !== this.#generation || !this.isConnected) {
      app.dispose();
      return;
    }
    this.#app = app;
    this.#applyParams();
    this.dispatchEvent(new CustomEvent('adasculpt-ready', { detail: app }));
  }

  #stop() {
    this.#generation++;
    if (this.#app) this.#app.dispose();
    this.#app = null;
  }

  #applyParams() {
    const params = {};
    for (const [attr, key] of Object.entries(PARAMS)) {
      if (this.hasAttribute(attr)) params[key] = paramValue(attr, this.getAttribute(attr));
    }
    if (Object.keys(params).length) this.#setParams(params);
  }

  #setParams(p) {
    try {
      this.#app.setParams(p);
    } catch (e) {
      this.#fail(e);
    }
  }

  #fail(error) {
    this.dispatchEvent(new CustomEvent('adasculpt-error', { detail: error }));
    console.warn(`<adasculpt-viewer>: ${error.message}`);
  }
}

function ensureStyle(doc) {
  if (doc.querySelector('style[data-adasculpt-viewer]')) return;
  const style = doc.createElement('style');
  style.dataset.adasculptViewer = '';
  style.textContent = ELEMENT_STYLE;
  doc.head.appendChild(style);
}

if (!customElements.get('adasculpt-viewer')) customElements.define('adasculpt-viewer', AdasculptViewerElement);
