// The app's camera gestures on top of OrbitControls (issue 19, View):
// - orbit around the point under the cursor: an orbit drag that starts over the model (the middle
//   button anywhere; the left button where no tool takes the press) turns the view around the surface
//   point under the press, which stays where it is on the screen; a drag from empty space turns around
//   the orbit centre as before;
// - touch: one finger off the model orbits, two fingers orbit and pinch-zoom (a finger on the model
//   sculpts: web/brush-tool.js holds the one-finger orbit off meanwhile).
//
// OrbitControls always turns the camera around its target. A turn R around the target T moves the
// camera (and leaves T); the same turn around a pivot P would also move both by (I - R)(P - T). So
// after each of OrbitControls' changes during such a drag, camera and target move by that vector
// (R from the camera's orientation before and after): the camera still looks at the target, and P,
// fixed in the world and seen from a camera turned around it, keeps its place on the screen.
import * as THREE from 'three';

// pick(clientX, clientY): the surface point under the pointer in world coordinates, or null.
export function createCameraGestures({ viewer, pick }) {
  const controls = viewer.controls;
  const canvas = viewer.renderer.domElement;
  controls.mouseButtons.MIDDLE = THREE.MOUSE.ROTATE; // the wheel zooms; the middle drag orbits
  controls.touches.TWO = THREE.TOUCH.DOLLY_ROTATE;   // pinch zooms, two fingers moving together orbit

  let pivot = null;   // world point the current drag turns around
  let lastPivot = null;
  const before = new THREE.Quaternion();
  const turn = new THREE.Quaternion();
  const arm = new THREE.Vector3();
  const shift = new THREE.Vector3();

  // After OrbitControls' own pointerdown (registered first); a tool that took the press stopped it.
  const onPointerDown = (e) => {
    pivot = null;
    if (e.pointerType === 'touch' || !controls.enabled || !rotates(e)) return;
    pivot = pick(e.clientX, e.clientY);
    if (pivot) lastPivot = pivot.clone();
    before.copy(viewer.camera.quaternion);
  };
  const onChange = () => {
    if (!pivot) return;
    const camera = viewer.camera;
    turn.copy(camera.quaternion).multiply(before.invert()); // R = q_after * q_before^-1
    before.copy(camera.quaternion);
    arm.copy(pivot).sub(controls.target);
    shift.copy(arm).sub(arm.applyQuaternion(turn)); // (I - R)(P - T)
    if (shift.lengthSq() === 0) return; // a pan or a zoom: no turn
    camera.position.add(shift);
    controls.target.add(shift);
    camera.updateMatrixWorld();
  };
  const onEnd = () => { pivot = null; };

  // Which presses OrbitControls turns a drag into an orbit (its mouseButtons, with its modifier rules).
  function rotates(e) {
    const action = e.button === 0 ? controls.mouseButtons.LEFT : e.button === 1 ? controls.mouseButtons.MIDDLE : null;
    if (action !== THREE.MOUSE.ROTATE) return false;
    return !(e.ctrlKey || e.metaKey || e.shiftKey); // OrbitControls pans with these held
  }

  canvas.addEventListener('pointerdown', onPointerDown);
  controls.addEventListener('change', onChange);
  controls.addEventListener('end', onEnd);
  return {
    // The surface point the last orbit drag over the model turned around (world), or null.
    get pivot() { return lastPivot ? lastPivot.clone() : null; },
    dispose() {
      canvas.removeEventListener('pointerdown', onPointerDown);
      controls.removeEventListener('change', onChange);
      controls.removeEventListener('end', onEnd);
    },
  };
}
