// Type declarations for `import 'adasculpt/element'` (web/viewer-element.js), hand-written.
import type { SculptApp } from './adasculpt';

export type { SculptApp } from './adasculpt';

/**
 * `<adasculpt-viewer src="model.obj" epsilon="0.05%" min-length="0.2%" max-length="5%" features="45"
 * handle-radius="4%" roi-radius="15%" ui="off" wasm-url="/wasm/adasculpt.js" autosave="my-key">`.
 * Attribute changes apply to the running app; removing the element disposes it. `autosave`: IndexedDB
 * autosave under that key (empty: `'viewer'`), see `SculptAppOptions.autosave`.
 */
export declare class AdasculptViewerElement extends HTMLElement {
  static readonly observedAttributes: string[];
  /** The page API once `adasculpt-ready` has fired; `null` before and after removal. */
  readonly app: SculptApp | null;
}

declare global {
  interface HTMLElementTagNameMap {
    'adasculpt-viewer': AdasculptViewerElement;
  }
  interface HTMLElementEventMap {
    'adasculpt-ready': CustomEvent<SculptApp>;
    'adasculpt-error': CustomEvent<Error>;
  }
}
