// The package's entry: `import { AdaptiveSculptor, createSculptApp } from 'adasculpt'`.
// Declarations and the API's documentation: web/adasculpt.d.ts.
export { AdaptiveSculptor } from './AdaptiveSculptor.js';
export { createSculptApp } from './app.js';
