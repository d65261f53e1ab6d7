// Type declarations for `import { createSculptApp } from 'adasculpt'` (web/app.js), hand-written.
// The custom element (`import 'adasculpt/element'`) is declared in viewer-element.d.ts.

/** A 3-vector: `[x, y, z]` or anything with numeric x, y, z (e.g. a THREE.Vector3). */
export type Vec3 = [number, number, number] | { x: number; y: number; z: number };

/** A length: a number is absolute (model units), a string `"0.05%"` is percent of the bounding-box diagonal. */
export type Length = number | `${number}%`;

export type MeshFormat = 'obj' | 'stl' | 'ply' | 'off';

/** What `load` accepts: a URL (fetched), a File/Blob, or the file's bytes. */
export type MeshSource = string | URL | Blob | ArrayBuffer | ArrayBufferView;

export interface SculptAppOptions {
  /** URL of the first model; `null` for none. Default: the bundled sphere (`models/sphere.obj`). */
  model?: string | null;
  /**
   * URL of the WebAssembly loader script `adasculpt.js` (adasculpt.wasm must sit next to it).
   * Default: `wasm/adasculpt.js` relative to the page (`document.baseURI`). The script is injected
   * once per page; every app gets its own module instance (own wasm memory).
   */
  wasmUrl?: string;
  /** Panel, stats overlay and help line. Default `true`. */
  ui?: boolean;
  /** `'global'`: keyboard shortcuts on `window`; default `'focus'`: only while the app has the focus. */
  keyboard?: 'global' | 'focus';
  /**
   * IndexedDB autosave under this key (one record per key): after each change, debounced, the mesh,
   * settings and newest undo steps are saved; on start-up a saved session is offered (Restore /
   * Discard). Default `false`; the standalone page uses `'main'`.
   */
  autosave?: string | false;
}

/** What an autosave record holds (without the data). */
export interface AutosaveInfo {
  key: string;
  /** Name of the file the session started from. */
  name: string;
  vertices: number;
  faces: number;
  /** `Date.now()` of the write. */
  savedAt: number;
  /** Size of the saved state (mesh + history) in bytes. */
  bytes: number;
}

export interface Autosave {
  /** False when the app was created without the `autosave` option (every method then does nothing). */
  readonly enabled: boolean;
  readonly key: string | null;
  /** A restore offer is on screen (nothing is written until it is answered). */
  readonly pending: boolean;
  /** The message of the last failed write, or null. */
  readonly lastError: string | null;
  /** Writes now if something changed since the last write; true when written. */
  flush(): Promise<boolean>;
  /** What is saved, or null. */
  saved(): Promise<AutosaveInfo | null>;
  /** Loads the saved mesh, settings and undo/redo history; null when nothing is saved. Rejects on a damaged record (the mesh stays). */
  restore(): Promise<Omit<AutosaveInfo, 'key' | 'bytes'> | null>;
  /** Deletes the saved record and hides the offer. */
  clear(): Promise<void>;
}

export interface SculptParams {
  /** Approximation tolerance (the method's one parameter). */
  epsilon?: Length;
  minLength?: Length;
  maxLength?: Length;
  /** Feature-edge dihedral angle in degrees; 0 = off. */
  features?: number;
  /** Default grab radii (geodesic) for mouse grabs and `grab.begin` without radii. */
  handleRadius?: Length;
  roiRadius?: Length;
  /** The brushes' radius, strength (0..1) and mirror symmetry (the panel's Brush folder; `brush.*` defaults). */
  brushRadius?: Length;
  brushStrength?: number;
  symmetry?: 'x' | 'y' | 'z' | 'off' | 'none';
}

/** The core's settings, absolute lengths. */
export interface CoreSettings {
  epsilon: number;
  min_length: number;
  max_length: number;
  features: number;
  diagonal: number;
}

export interface GrabBegin {
  /** Snapped to the closest surface point. */
  center: Vec3;
  /** Absolute lengths; default: the panel's radii. */
  handleRadius?: number;
  roiRadius?: number;
}

/** The total transform since `grab.begin` (not an increment). */
export interface GrabTransform {
  translate?: Vec3;
  rotate?: { axis: Vec3; degrees: number };
  scale?: number;
}

export interface FrameTimings {
  roi: number; field: number; refine: number; deform: number; remesh: number; total: number;
  /** Render-buffer update in wasm after the core's work. */
  buffers: number;
  /** Brush stamps run in the frame (0 for grab frames). */
  stamps: number;
}

/** The core's brushes; `'grab'` is the snake hook (the surface under the press follows the pointer). */
export type BrushToolName = 'draw' | 'inflate' | 'smooth' | 'flatten' | 'pinch' | 'crease' | 'grab';
/** What the pointer drives: `'pull'` is the handle grab (`app.grab`), the others are brushes. */
export type ToolName = 'pull' | BrushToolName;

/** Brush settings; the missing ones come from the panel (radius, strength, symmetry X by default). */
export interface BrushSettings {
  /** Default: the current tool when it is a brush, else `'draw'`. */
  tool?: BrushToolName;
  /** Absolute length. */
  radius?: number;
  /** 0..1 (pressure multiplies it). */
  strength?: number;
  /** Mirror across the plane x, y or z = 0; `'off'` (or `'none'`) for none. */
  symmetry?: 'x' | 'y' | 'z' | 'off' | 'none';
  /** Draw/inflate/crease inwards, flatten/pinch push away. */
  invert?: boolean;
  /** A stamp every `spacing` × radius of travel (0.05..4, default 0.25). */
  spacing?: number;
}

export interface BrushStroke extends BrushSettings {
  /** Surface points along the stroke (for the grab brush: the pointer positions in space). */
  path: Vec3[];
  /** One value in 0..1 per path point; default 1. */
  pressure?: number[];
}

export interface SculptStats {
  vertices: number;
  faces: number;
  minAngle: number | null;
  meanMinAngle: number | null;
  lastFrameMs: number;
  coreMs: number;
  buffersMs: number;
  phasesMs: Partial<FrameTimings>;
  uploadMs: number;
  renderMs: number;
  /** `performance.now()` of the first frame that showed a mesh. */
  firstRenderMs: number | null;
  wasmReadyMs: number;
  canUndo: boolean;
  canRedo: boolean;
  settings: CoreSettings;
  /** The core's quality report (angles, valences, edge lengths, ...). */
  quality: Record<string, unknown>;
}

/** The same JSON object as `adasculpt replay --json` prints. */
export type ReplayReport = Record<string, unknown>;

export interface FrameLogEntry {
  coreMs: number; buffersMs: number; copyMs: number; renderMs: number; totalMs: number;
  phases: Partial<FrameTimings>;
  vertices: number;
}

/** The page API: `window.app` on the standalone page, or what `createSculptApp` resolves to. */
export interface SculptApp {
  /**
   * Replaces the mesh (undo history and settings reset). Rejects with the reader's message; the mesh stays.
   * A file that would need more wasm memory than the page can use (2 GB minus the current mesh and its
   * history; estimated from the header or the size) is refused before it is read.
   */
  load(source: MeshSource, format?: MeshFormat): Promise<{ vertices: number; faces: number }>;
  /** Throws on an unknown key or a bad value (nothing changes then). Returns the core's settings. */
  setParams(params: SculptParams): CoreSettings;
  readonly grab: {
    begin(args: GrabBegin): void;
    /** One frame: deform, refine, remesh the region; returns the mesh size and the frame's timings. */
    drag(transform: GrabTransform): { vertices: number; faces: number; timings: FrameTimings };
    /** The grab becomes one undo step. */
    end(): void;
  };
  /**
   * Brush strokes with dynamic topology; a stroke is one undo step. `stroke` runs a whole stroke
   * (the same as a session file's brush step); `begin`/`stamp`/`end` are the per-frame path the
   * mouse uses: `stamp` takes all of a frame's samples as `[x, y, z, pressure, ...]` in one wasm call.
   */
  readonly brush: {
    stroke(stroke: BrushStroke): { vertices: number; faces: number; timings: FrameTimings };
    begin(settings?: BrushSettings): void;
    stamp(samples: ArrayLike<number>): { vertices: number; faces: number; timings: FrameTimings };
    end(): void;
  };
  /** The current tool (palette, keys 1-8). */
  readonly tool: ToolName;
  /** Picks the tool; false while a grab or stroke is under way; throws on an unknown name. */
  setTool(name: ToolName): boolean;
  /** Whole-mesh remeshing, one iteration per animation frame, each one undo step. */
  remesh(options?: { iterations?: number }): Promise<SculptStats>;
  undo(): boolean;
  redo(): boolean;
  /** Runs a session file (`{"version":1,"settings":{...},"steps":[...]}`) on the current mesh. */
  replay(session: string | object): Promise<ReplayReport>;
  stats(): SculptStats;
  /** The current mesh as a file: OBJ/OFF with round-trip (17 digit) coordinates, binary PLY with doubles, STL (float32 by the format). */
  export(format?: MeshFormat): Promise<ArrayBuffer>;
  bounds(): { min: [number, number, number]; max: [number, number, number] };
  /** The per-grab-frame timings since the last call (benchmarks). */
  takeFrameLog(): FrameLogEntry[];
  /** Frees the wasm Session and instance, GPU resources (geometries, materials, textures, the WebGL context), the DOM it added and every listener. Idempotent. */
  dispose(): void;
  /** The IndexedDB autosave (see `SculptAppOptions.autosave`). */
  readonly autosave: Autosave;
  /** The Emscripten module instance of this app (advanced use). */
  readonly module: unknown;
  /** The embind `Session` of this app (advanced use; deleted by `dispose`). Its `positions()`/`indices()` are
   * the render buffers, one entry per vertex/face slot: faces deleted by remeshing stay as (0, 0, 0) triangles
   * until the core compacts the mesh (at the end of a grab or stroke once deleted slots are an eighth, and on
   * load, remesh, undo and redo). `export` and `stats` give the compacted mesh. */
  readonly session: unknown;
}

export function createSculptApp(container: HTMLElement, options?: SculptAppOptions): Promise<SculptApp>;
