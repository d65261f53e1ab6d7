// A generated torus (radii 1 and 0.3) of about `faces` triangles, as flat arrays for Session.loadArrays:
// the large meshes of the wasm benchmarks, made in memory instead of read from a file.
export function torusArrays(faces) {
  const n = Math.round(Math.sqrt(faces / 2) * 1.5), m = Math.round(faces / 2 / n);
  const p = new Float64Array(3 * n * m), t = new Uint32Array(6 * n * m);
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < m; j++) {
      const u = (2 * Math.PI * i) / n, v = (2 * Math.PI * j) / m, r = 1 + 0.3 * Math.cos(v), k = i * m + j;
      p.set([r * Math.cos(u), r * Math.sin(u), 0.3 * Math.sin(v)], 3 * k);
      const a = k, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + ((j + 1) % m), d = i * m + ((j + 1) % m);
      t.set([a, b, c, a, c, d], 6 * k);
    }
  }
  return { p, t };
}
