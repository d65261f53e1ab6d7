// Nothing adasculpt-specific: the package's wasm is found through `new URL(..., import.meta.url)`.
export default { build: { target: 'es2022' }, preview: { host: '127.0.0.1', strictPort: true } };
