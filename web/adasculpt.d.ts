// The JavaScript API of adasculpt, declared and documented in this one file (hand-written; checked
// by `tsc --noEmit` on tests/types/example.ts in `npm test`).
//
//   import { AdaptiveSculptor, createSculptApp } from 'adasculpt';   // web/index.js
//   import 'adasculpt/element';                                       // <adasculpt-viewer>, viewer-element.d.ts
//
// Conventions, everywhere: plain objects with camelCase keys in and out; a length is a number
// (absolute, in the mesh's own units) or a string "x%" (percent of the mesh's bounding-box
// diagonal); errors are thrown `Error`s whose message names the field. Session files
// (`replay`) are the file format the CLI reads, with its snake_case keys.
import type { Camera, EventDispatcher, Mesh, BufferGeometry, Vector3 } from 'three';

/** A 3-vector: `[x, y, z]` or anything with numeric x, y, z (e.g. a THREE.Vector3). */
export type Vec3 = [number, number, number] | { x: number; y: number; z: number };

/** A number is absolute (the mesh's own units), a string `"0.05%"` is percent of the bounding-box diagonal. */
export type Length = number | `${number}%`;

export type MeshFormat = 'obj' | 'stl' | 'ply' | 'off';

/** The core's brushes. `'snakeHook'` drags the surface under the press along (its old name `'grab'` is still read in session files). */
export type BrushToolName = 'draw' | 'inflate' | 'smooth' | 'flatten' | 'pinch' | 'crease' | 'snakeHook';
/** What the pointer drives: `'pull'` is the paper's handle grab (`grab.begin/drag/end`), `'mask'` paints the mask (`mask`), the others are brushes. */
export type ToolName = 'pull' | BrushToolName | 'mask';

/** Mirror strokes across the plane x, y or z = 0 of the mesh's own coordinates; `'off'` (or `'none'`) for none. */
export type Symmetry = 'x' | 'y' | 'z' | 'off' | 'none';

/**
 * How a stamp fades from its centre to its rim (q = distance / radius): `'smooth'` (1 − q²)³ (default,
 * every stroke before presets), `'sphere'` √(1 − q²), `'sharp'` (1 − q)², `'linear'` 1 − q, `'constant'` 1.
 */
export type BrushFalloff = 'smooth' | 'sphere' | 'sharp' | 'linear' | 'constant';

/**
 * What edge length strokes (and the detail flood fill) remesh to: `'relative'` the remesh settings
 * (ε, min/max length; default); `'constant'` `constantDetail`; `'brush'` `brushDetail` percent of the
 * brush radius; `'pixels'` `pixelDetail` screen pixels at the brush (the size follows the zoom).
 */
export type DetailMode = 'relative' | 'constant' | 'brush' | 'pixels';

/** Brush feel and detail (web/brush-feel.js). */
export interface FeelParams {
  /** Default `'smooth'`. */
  falloff?: BrushFalloff;
  /** A stamp every `spacing` × radius of pointer travel, 0.05..4 (default 0.25). */
  spacing?: number;
  /** Stroke stabiliser (lazy mouse): the brush trails the pointer on a string this many screen pixels long; 0 (default) off, up to 200. */
  stabilizer?: number;
  detailMode?: DetailMode;
  /** The `'constant'` mode's edge length. Default `"0.8%"`. */
  constantDetail?: Length;
  /** The `'brush'` mode's edge length in percent of the brush radius, 1..100 (default 15). */
  brushDetail?: number;
  /** The `'pixels'` mode's edge length in screen pixels, 1..100 (default 8). */
  pixelDetail?: number;
}

/** Remeshing settings (the method's parameters). */
export interface RemeshParams {
  /** Approximation tolerance ε: the sizing field is L = sqrt(6ε/κ − 3ε²). Default `"0.05%"`. */
  epsilon?: Length;
  /** Shortest and longest target edge. Defaults `"0.2%"`, `"5%"`. */
  minLength?: Length;
  maxLength?: Length;
  /** Feature-edge dihedral angle in degrees; 0 = off (default). */
  features?: number;
  /** Strokes and grabs remesh without creating crossing triangles (hard pinches and creases); frames cost about 1.6x. Default false; kept through loads. */
  guardCrossings?: boolean;
}

/** The tools' settings. Defaults: `tool 'draw'` (the app: `'pull'`), radius `"5%"`, strength 0.5, symmetry `'x'`, handle `"4%"`, region `"15%"`. */
export interface ToolParams {
  tool?: ToolName;
  /** The brushes' radius. */
  radius?: Length;
  /** 0..1; a pen's pressure multiplies it. */
  strength?: number;
  symmetry?: Symmetry;
  /** The Pull tool's handle and region-of-interest radii (geodesic). */
  handleRadius?: Length;
  roiRadius?: Length;
}

/** The core's remeshing settings, absolute lengths. */
export interface CoreSettings {
  epsilon: number;
  minLength: number;
  maxLength: number;
  features: number;
  guardCrossings: boolean;
  /** Bounding-box diagonal of the mesh as loaded (what "x%" lengths are relative to). */
  diagonal: number;
}

/** Everything adjustable, lengths absolute. Remeshing settings are `null` without a mesh. */
export interface SculptorParams {
  epsilon: number | null;
  minLength: number | null;
  maxLength: number | null;
  features: number | null;
  guardCrossings: boolean | null;
  diagonal: number;
  tool: ToolName;
  radius: number;
  strength: number;
  symmetry: 'x' | 'y' | 'z' | 'off';
  handleRadius: number;
  roiRadius: number;
  falloff: BrushFalloff;
  spacing: number;
  stabilizer: number;
  detailMode: DetailMode;
  /** Absolute (its percent in `percent.constantDetail`). */
  constantDetail: number;
  brushDetail: number;
  pixelDetail: number;
  /** The tool lengths in percent of the diagonal (they keep their share when another mesh is loaded). */
  percent: { radius: number; handleRadius: number; roiRadius: number; constantDetail: number };
}

/** Milliseconds of one frame in the core (`stamps`: brush stamps run in it; 0 for grab frames). */
export interface FrameTimings {
  roi: number; field: number; refine: number; deform: number; remesh: number; total: number;
  /** Render-buffer update in wasm after the core's work. */
  buffers: number;
  stamps: number;
  /** Grab frames: the ROI was cut to its vertex budget, and the vertices it holds. */
  roiCapped?: boolean;
  roiVertices?: number;
  /** Grab frames: the vertices the frame remeshed (what the drag strained since they last were). */
  remeshedVertices?: number;
  /** Grab frames: the frame applied a finished solve of the blending field. */
  fieldRefreshed?: boolean;
}

/** A whole stroke's figures (`end` event): frames with a core call, core + buffer ms per frame. */
export interface StrokeTimings {
  frames: number;
  stamps: number;
  /** Wall time from the press (or `begin`) to the end. */
  durationMs: number;
  /** Sum over the frames of core + render-buffer ms. */
  coreMs: number;
  medianFrameMs: number;
  p95FrameMs: number;
  maxFrameMs: number;
}

export interface MeshCounts { vertices: number; faces: number }

/** One frame of a stroke: the mesh's size and the frame's timings. */
export interface FrameResult extends MeshCounts { timings: FrameTimings }

/** The events of `AdaptiveSculptor` and of the app (`start`, `change`, `end`). */
export interface SculptorEventMap {
  /** A stroke (grab or brush, by pointer or API) began. */
  start: { tool: ToolName };
  /**
   * Something to draw changed: after each stroke frame, undo, redo, load or remesh (with the mesh's
   * size, the core's timings and the copy into the geometry), or only the cursor (no fields).
   */
  change: Partial<FrameResult> & { copyMs?: number };
  /** A stroke ended: one undo step. */
  end: MeshCounts & { tool: ToolName; timings: StrokeTimings };
  /** The current tool changed (`setTool`, the app's keys 1–8). */
  tool: { tool: ToolName };
  /** Tool settings changed (`setParams`, or the keys `[ ] { } - =`). */
  params: {};
  /** A pointer-driven action failed (without a listener, the error goes to console.error). */
  error: { error: Error };
  dispose: {};
}

export interface GrabBegin {
  /** Snapped to the closest surface point (the mesh's own coordinates). */
  center: Vec3;
  /** Absolute lengths; default: the current `handleRadius`/`roiRadius`. */
  handleRadius?: number;
  roiRadius?: number;
}

/** The total transform since `grab.begin` (not an increment). */
export interface GrabTransform {
  translate?: Vec3;
  rotate?: { axis: Vec3; degrees: number };
  scale?: number;
}

/** Brush settings; the missing ones are the current ones (`setParams`). */
export interface BrushSettings {
  /** Default: the current tool when it is a brush, else `'draw'`. */
  tool?: BrushToolName;
  /** Absolute length. */
  radius?: number;
  strength?: number;
  symmetry?: Symmetry;
  /** Draw/inflate/crease inwards, flatten/pinch push away. */
  invert?: boolean;
  /** A stamp every `spacing` × radius of travel (0.05..4; default: the current `spacing`, 0.25). */
  spacing?: number;
  /** Default: the current `falloff`. */
  falloff?: BrushFalloff;
  /** This stroke's edge length (absolute); 0: the remesh settings. Default: the current detail mode's (`detailLength()`). */
  detail?: number;
}

export interface BrushStroke extends BrushSettings {
  /** Surface points along the stroke (for the snake hook: the pointer positions in space). */
  path: Vec3[];
  /** One value in 0..1 per path point; default 1. */
  pressure?: number[];
}

/** Programmatic handle grabs (the Pull tool's path), each `begin`..`end` one undo step. */
export interface GrabApi {
  begin(args: GrabBegin): void;
  /** One frame: deform, refine, remesh the region. */
  drag(transform: GrabTransform): FrameResult;
  end(): void;
}

/**
 * Programmatic brush strokes with dynamic topology, each one undo step. `stroke` runs a whole stroke
 * (the same as a session file's brush step); `begin`/`stamp`/`end` are the per-frame path the pointer
 * uses: `stamp` takes a frame's samples as `[x, y, z, pressure, ...]` in one wasm call.
 */
export interface BrushApi {
  stroke(stroke: BrushStroke): FrameResult;
  begin(settings?: BrushSettings): void;
  stamp(samples: ArrayLike<number>): FrameResult;
  end(): void;
}

/** A mask stroke's settings; the missing ones are the brush's current radius and strength. */
export interface MaskSettings {
  /** Lower the mask instead of raising it (the pointer: Ctrl or Alt held at the press). */
  erase?: boolean;
  /** Absolute length; the stroke is solid over half of it and fades out to it. */
  radius?: number;
  /** 0..1: the mask value a paint stroke raises to (erase: lowers to 1 − strength). */
  strength?: number;
}

/**
 * The sculpting mask: one value in 0..1 per vertex. Fully masked vertices never move under any
 * tool or pull and their triangles are not remeshed; partly masked ones move by (1 − mask). Shown
 * as a dark tint (the geometry's `mask` attribute). Every operation is one undo step, dispatches
 * `start`/`end` (tool `'mask'`), is kept by autosave and is a session file's `{"mask": {...}}` step.
 */
export interface MaskApi {
  /** Every vertex to 0. */
  clear(): void;
  /** Every vertex to 1. */
  fill(): void;
  /** Every vertex to 1 − mask. */
  invert(): void;
  /** Every vertex to the mean of itself and its neighbours. */
  blur(): void;
  /** Every vertex to smoothstep(mask): away from ½ towards 0 or 1. */
  sharpen(): void;
  /** A whole paint (or erase) stroke along surface points. */
  stroke(stroke: MaskSettings & { path: Vec3[] }): FrameResult;
  /** The pointer's path: begin, a frame's surface points `[x, y, z, ...]` per `stamp`, end. */
  begin(settings?: MaskSettings): void;
  stamp(points: ArrayLike<number>): FrameResult;
  end(): void;
  /** A copy of the mask per vertex slot (the render buffers' numbering; 0 where unmasked or deleted). */
  values(): Float32Array;
}

/** The same object as `adasculpt replay --json` prints, keys in camelCase (frames, frameMsMedian, frameMsP95, vertices, minAngleDeg, ...). */
export type ReplayReport = Record<string, unknown>;

/** A session file: `{"version": 1, "settings": {...}, "steps": [{"grab": ...}, {"brush": ...}, {"remesh": ...}, {"mask": {"op": ...}}, {"undo": n}, {"redo": n}]}` (cpp/sculpt/session_file.h). */
export type SessionFile = string | { version: 1; settings?: Record<string, unknown>; steps: Record<string, unknown>[] };

export interface SculptorOptions extends RemeshParams, ToolParams, FeelParams {
  /**
   * URL of the WebAssembly loader `adasculpt.js` (adasculpt.wasm next to it). Default: the package's
   * own copy, found with `new URL(..., import.meta.url)` (bundlers copy both files into the build).
   */
  wasmUrl?: string;
  /** Where keyboard shortcuts are heard (`[ ]` radius, `- =` strength, R/S/G during a pull); default none. */
  keyTarget?: EventTarget | null;
  /**
   * The host's OrbitControls (or anything with `enabled`): disabled while a stroke runs; with `touches`,
   * its one-finger action is held off while a finger rests on the model (a finger on the model sculpts,
   * two fingers are the controls').
   */
  controls?: { enabled: boolean; touches?: { ONE?: unknown } } | null;
  /** Also keep a wireframe index geometry (`buffers.lines`). */
  wireframe?: boolean;
  /** Draw the Pull tool's handle/region preview yourself (default: rings on the surface). */
  grabPreview?: (preview: { center?: Vector3; handleRadius: number; roiRadius: number; visible: boolean }) => void;
  /** An Emscripten module instance to use instead of creating one (advanced). */
  module?: AdasculptModule;
}

/**
 * Sculpts the host's own `THREE.Mesh` with adaptive remeshing under every stroke. The mesh's
 * BufferGeometry is changed in place (same object; position, normal and index attributes of the
 * core's capacity, uploaded by dirty ranges; other attributes such as uv are removed, since the
 * vertices change). Pointer rays go through `mesh.matrixWorld`: lengths are in the geometry's units.
 * It never renders: listen to `change`, or render every frame.
 *
 * A press on the mesh strokes with the current tool (Ctrl or Alt held: inverted); a press elsewhere
 * is left to the host (e.g. OrbitControls on the same element). Pointer capture keeps a stroke
 * going outside the element.
 */
export declare class AdaptiveSculptor extends EventDispatcher<SculptorEventMap> {
  /** Loads the wasm module (see `wasmUrl`), welds the mesh's triangles by position and takes them over. */
  static create(mesh: Mesh, camera: Camera, options?: SculptorOptions): Promise<AdaptiveSculptor>;

  readonly mesh: Mesh;
  camera: Camera;
  /** The element given to `connect`, or null. */
  readonly domElement: HTMLElement | null;
  /** False: `update()` does nothing (pointer samples wait). */
  enabled: boolean;
  readonly tool: ToolName;
  /** Absolute lengths. */
  readonly radius: number;
  readonly handleRadius: number;
  readonly roiRadius: number;
  readonly strength: number;
  readonly symmetry: 'x' | 'y' | 'z' | 'off';
  /** Bounding-box diagonal of the mesh as loaded. */
  readonly diagonal: number;
  /** A whole-mesh remesh is running. */
  readonly busy: boolean;
  readonly params: SculptorParams;
  /** The embind session (advanced; deleted by `dispose`). */
  readonly session: Session;
  readonly module: AdasculptModule | null;
  /** Programmatic strokes; they dispatch `start`/`change`/`end` like the pointer's. */
  readonly grab: GrabApi;
  readonly brush: BrushApi;
  readonly mask: MaskApi;

  /** Listens to pointer events (and wheel) on the element until `disconnect()`. */
  connect(domElement: HTMLElement): void;
  disconnect(): void;
  /** False (nothing changes) while a stroke runs; throws on an unknown name. */
  setTool(name: ToolName): boolean;
  /** Checks every value first, then applies them; throws on an unknown key or a bad value. */
  setParams(params: RemeshParams & ToolParams & FeelParams): SculptorParams;
  /** Replaces the surface by this geometry's triangles (welded by position); history and settings start afresh. */
  loadGeometry(geometry: BufferGeometry): void;
  /** Replaces the surface by a mesh file (OBJ, STL, PLY, OFF; `name`'s extension gives the format). */
  loadBytes(bytes: Uint8Array | ArrayBuffer, name: string): void;
  /** Re-reads the whole surface from `session` (after calling its methods directly). */
  resync(): void;
  /** Whole strokes; false when there is nothing to undo/redo or a stroke runs. */
  undo(): boolean;
  redo(): boolean;
  /**
   * Whole-mesh adaptive remeshing with projection onto the current surface. Without `onProgress`: one
   * core call of `iterations` (default 5), one undo step, the CLI's `remesh --iterations` result.
   * With `onProgress`: reported before (`done: 0`, one animation frame passes) and after the same single call.
   */
  remesh(options?: { iterations?: number; detail?: number; onProgress?: (p: { done: number; total: number }) => void }): Promise<MeshCounts>;
  /**
   * The detail flood fill: `remesh` with `detail: detailLength()`, the whole mesh at the edge length strokes
   * get now (in `'relative'` mode, the remesh settings). One core call, one undo step.
   */
  floodFill(options?: { iterations?: number; onProgress?: (p: { done: number; total: number }) => void }): Promise<MeshCounts>;
  /**
   * The edge length (absolute) a stroke at `point` (the mesh's coordinates; default the middle of its
   * bounds, which only matters in `'pixels'` mode) remeshes to; 0 in `'relative'` mode.
   */
  detailLength(point?: Vector3): number;
  /** The surface point under a pointer position (client pixels), world coordinates; null off the model or before `connect`. */
  surfacePoint(clientX: number, clientY: number): Vector3 | null;
  /** Runs a session file on the current mesh. */
  replay(file: SessionFile): ReplayReport;
  /** Sends the pointer samples queued since the last frame to the core now (it also schedules itself). */
  update(): void;
  /** Frees the wasm instance, the cursor (geometry, materials) and every listener; the mesh keeps the sculpted geometry. Idempotent. */
  dispose(): void;
}

// ---------------------------------------------------------------------------------------------
// The app

/** What `load` accepts: a URL (fetched), a File/Blob, or the file's bytes. */
export type MeshSource = string | URL | Blob | ArrayBuffer | ArrayBufferView;

export interface SculptAppOptions {
  /** URL of the first model; `null` for none. Default: the bundled sphere (`models/sphere.obj`, relative to the page). */
  model?: string | null;
  /** As `SculptorOptions.wasmUrl`. */
  wasmUrl?: string;
  /** Panel, tool palette, stats overlay and help line. Default `true`. */
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
  /** Size of the saved state (mesh + history) in bytes: the whole state plus its change records. */
  bytes: number;
  /** Change records written after the whole state (each the changes of one autosave). */
  changes: number;
  /** Size of the newest record (the whole state's when there is none). */
  lastBytes: number;
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
  saved(): Promise<AutosaveInfo | null>;
  /** Loads the saved mesh, settings and undo/redo history; null when nothing is saved. Rejects on a damaged record (the mesh stays). */
  restore(): Promise<Omit<AutosaveInfo, 'key' | 'bytes'> | null>;
  /** Deletes the saved record and hides the offer. */
  clear(): Promise<void>;
}

/** `setParams` of the app: the sculptor's, plus the older names `brushRadius`/`brushStrength` of `radius`/`strength`. */
export interface SculptParams extends RemeshParams, Omit<ToolParams, 'tool'>, FeelParams {
  brushRadius?: Length;
  brushStrength?: number;
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
  /** The core's whole quality report (`session.stats()`), computed when read (a pass over the mesh). */
  readonly quality: QualityReport;
}

export interface FrameLogEntry {
  coreMs: number; buffersMs: number; copyMs: number; renderMs: number; totalMs: number;
  phases: Partial<FrameTimings>;
  vertices: number;
}

/** The page API: `window.app` on the standalone page, or what `createSculptApp` resolves to. Dispatches the sculptor's `start`, `change` and `end`. */
export interface SculptApp extends EventDispatcher<Pick<SculptorEventMap, 'start' | 'change' | 'end'>> {
  /**
   * Replaces the mesh (undo history and settings reset). Rejects with the reader's message; the mesh stays.
   * A file that would need more wasm memory than the page can use (2 GB minus the current mesh and its
   * history; estimated from the header or the size) is refused before it is read.
   */
  load(source: MeshSource, format?: MeshFormat): Promise<MeshCounts & { warnings: string[] }>;
  /** Throws on an unknown key or a bad value (nothing changes then). Returns the core's settings. */
  setParams(params: SculptParams): CoreSettings;
  readonly grab: GrabApi;
  readonly brush: BrushApi;
  /** The mask (`app.mask.clear()`, `invert()`, ...; the tool `'mask'`, key M, paints it). */
  readonly mask: MaskApi;
  /** The current tool (palette, keys 1–8 and M). */
  readonly tool: ToolName;
  setTool(name: ToolName): boolean;
  /**
   * The camera. `frame()`: the model fills the free part of the canvas (F, Home); `set(name)`: an axis
   * view, framed (Shift+1–6, numpad 1/3/7 and Ctrl+numpad); `orthographic(on?)`: switches (O, numpad 5)
   * and returns whether it is. Zoom limits follow the model's size (set by each frame/set/load).
   * An orbit drag starting over the model (middle button) turns around the surface point under the press;
   * `state().pivot` is the last such point (world), null before.
   */
  readonly view: {
    frame(): void;
    set(name: 'front' | 'back' | 'left' | 'right' | 'top' | 'bottom'): void;
    orthographic(on?: boolean): boolean;
    state(): {
      position: number[]; target: number[]; up: number[]; distance: number; zoom: number; orthographic: boolean;
      minDistance: number; maxDistance: number; minZoom: number; maxZoom: number; modelRadius: number;
      pivot: number[] | null;
    };
  };
  /** Looks (panel: Display): matcap ('clay', 'red wax', 'jade', 'blue steel', 'chalk'), material, flat shading, wireframe overlay. Returns the current ones. */
  display(d?: { matcap?: string; shading?: 'matcap' | 'standard'; flat?: boolean; wireframe?: boolean }):
    { matcap: string; shading: 'matcap' | 'standard'; flat: boolean; wireframe: boolean };
  /** Whole-mesh remeshing: one core call of `iterations` (the CLI's result, one undo step) with a progress display. */
  remesh(options?: { iterations?: number }): Promise<SculptStats>;
  /** The detail flood fill (panel › Detail): `sculptor.floodFill` with the panel's progress; one undo step. */
  floodFill(options?: { iterations?: number }): Promise<SculptStats>;
  undo(): boolean;
  redo(): boolean;
  replay(session: SessionFile): Promise<ReplayReport>;
  stats(): SculptStats;
  /** The current mesh as a file: OBJ/OFF with round-trip (17 digit) coordinates, binary PLY with doubles, STL (float32 by the format). */
  export(format?: MeshFormat): Promise<ArrayBuffer>;
  bounds(): { min: [number, number, number]; max: [number, number, number] };
  /** The per-stroke-frame timings since the last call (benchmarks). */
  takeFrameLog(): FrameLogEntry[];
  /** Frees the wasm instance, GPU resources (geometries, materials, textures, the WebGL context), the DOM it added and every listener. Idempotent. */
  dispose(): void;
  readonly autosave: Autosave;
  /** The sculptor the app drives (its mesh is the app's surface). */
  readonly sculptor: AdaptiveSculptor;
  readonly module: AdasculptModule;
  readonly session: Session;
}

export function createSculptApp(container: HTMLElement, options?: SculptAppOptions): Promise<SculptApp>;

// ---------------------------------------------------------------------------------------------
// The WebAssembly module (cpp/bindings/bindings.cpp), for advanced use and node

/** The core's quality report (`adasculpt stats --json` in camelCase). */
export interface QualityReport {
  vertices?: number; faces?: number; edges?: number; boundaryLoops?: number; components?: number; genus?: number;
  minAngleDeg?: number; maxAngleDeg?: number; meanMinAngleDeg?: number; pctMinAngleLt30?: number; pctMinAngleLt10?: number;
  valence6Pct?: number; valenceHistogram?: Record<string, number>;
  edgeLengthMin?: number; edgeLengthMean?: number; edgeLengthMax?: number; edgeLengthStd?: number;
  degenerateFaces?: number; bboxDiag?: number; area?: number;
  lastFrame: { roiMs: number; fieldMs: number; refineMs: number; deformMs: number; remeshMs: number; totalMs: number };
  canUndo: boolean;
  canRedo: boolean;
  [key: string]: unknown;
}

/** What a frame call returns: dirty slot ranges, capacities and byte addresses of the render buffers in wasm memory. */
export interface RenderChanges extends MeshCounts {
  reallocated: boolean; indicesChanged: boolean;
  vertexBegin: number; vertexEnd: number; faceBegin: number; faceEnd: number;
  vertexCount: number; faceCount: number; vertexCapacity: number; faceCapacity: number;
  positionsPtr: number; normalsPtr: number; masksPtr: number; indicesPtr: number;
  /** The face slots whose triangle changed (uint32 at dirtyFacesPtr, valid until the next call), or all of them when allFacesDirty. */
  allFacesDirty: boolean; dirtyFacesPtr: number; dirtyFaceCount: number;
  timings: FrameTimings;
}

/**
 * `new module.Session()`: one mesh, its settings and undo history. C++ errors are thrown as `Error`s
 * with the core's message. Call `delete()` when done (embind objects are not garbage-collected).
 */
export interface Session {
  hasMesh(): boolean;
  loadBytes(bytes: Uint8Array | ArrayBuffer, nameHint: string): void;
  loadArrays(positions: ArrayLike<number>, indices: ArrayLike<number>): void;
  /** What the reader repaired in the last load ("reversed 12 face(s) to orient the surface consistently"); [] when nothing. */
  loadWarnings(): string[];
  setSettings(settings: RemeshParams): void;
  settings(): CoreSettings;
  pick(ox: number, oy: number, oz: number, dx: number, dy: number, dz: number): { hit: boolean; x: number; y: number; z: number };
  grabBegin(cx: number, cy: number, cz: number, handleRadius: number, roiRadius: number): void;
  grabDrag(tx: number, ty: number, tz: number, ax: number, ay: number, az: number, degrees: number, scale: number): RenderChanges;
  grabEnd(): void;
  grabbing(): boolean;
  brushBegin(settings: BrushSettings & { tool: BrushToolName; radius: number }): void;
  brushStamp(samples: Float64Array): RenderChanges;
  brushEnd(): void;
  brushing(): boolean;
  /** A mask operation, one undo step: `{op: 'clear' | 'fill' | 'invert' | 'blur' | 'sharpen'}` or `{op: 'paint' | 'erase', path: [[x, y, z], ...], radius, strength?}`. */
  mask(op: { op: string; path?: number[][]; radius?: number; strength?: number }): RenderChanges;
  maskBegin(op: { op: 'paint' | 'erase'; radius: number; strength?: number }): void;
  maskStamp(points: Float64Array): RenderChanges;
  maskEnd(): void;
  masking(): boolean;
  /** The mask per vertex slot, a view into wasm memory like `positions()`. */
  maskValues(): Float32Array;
  remesh(iterations: number): void;
  /** `remesh` towards a constant edge length `detail` (absolute; 0: the settings). */
  remeshDetail(iterations: number, detail: number): void;
  undo(): boolean;
  redo(): boolean;
  canUndo(): boolean;
  canRedo(): boolean;
  replay(file: SessionFile): ReplayReport;
  /** The whole quality report: a pass over the mesh (about 0.9 s at 1.1M triangles), not for every stroke. */
  stats(): QualityReport;
  /** What a viewer shows after every stroke, kept up to date from the changes (costs what changed):
   *  vertices, faces, edges, min/max angle, mean min angle, shares under 30 and 10 degrees, as stats()
   *  gives them; the other quality keys are 0. */
  quickStats(): QualityReport;
  exportMesh(format: MeshFormat): Uint8Array;
  /** The whole state (mesh, settings, history within the budget); starts a chain of change records. */
  saveState(maxHistoryBytes: number): Uint8Array;
  /** The changes since the last saveState/saveChanges as the chain's next small record; null when a
   *  whole state is due (nothing saved yet, a load or whole remesh since, an undo past the saved history). */
  saveChanges(): Uint8Array | null;
  restoreState(bytes: Uint8Array): void;
  /** A saveState blob, then its change records in order; all or nothing (throws "saved state: ..."). */
  restoreSaved(bytes: Uint8Array, changes: Uint8Array[]): void;
  memoryBytes(): number;
  positions(): Float32Array;
  normals(): Float32Array;
  indices(): Uint32Array;
  changes(): RenderChanges;
  delete(): void;
}

export interface AdasculptModule {
  Session: new () => Session;
  /** What a new session starts with: `{epsilon: "0.05%", minLength: "0.2%", maxLength: "5%", features: 0}`. */
  defaultSettings(): Required<RemeshParams>;
  HEAPU8: Uint8Array;
}
