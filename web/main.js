// The standalone page: the app fills the window and is scriptable as window.app.
import { createSculptApp } from './app.js';

const params = new URLSearchParams(location.search);
const model = params.get('model') || undefined; // e.g. ?model=models/fandisk.off
window.createSculptApp = createSculptApp; // for scripting more instances (and the dispose test)
window.app = await createSculptApp(document.getElementById('sculpt'), { keyboard: 'global', autosave: 'main', ...(model ? { model } : {}) });
document.documentElement.dataset.ready = 'true';
