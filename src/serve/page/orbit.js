// Turning and zooming the 3D view (view3d.js) by hand: drag to orbit (AZ
// with the pointer across, EL up and down, 0.4 degrees a pixel), the
// wheel to zoom, and the same from the keyboard once the view has focus
// (click it or Tab to it): the arrow keys turn by 5 degrees (15 with
// Shift), + and - zoom, 0 (or Home) fits again as the Fit button does.

export const DEG_PER_PX = 0.4;
const KEY_STEP = 5;
const ZOOM_STEP = 1.15;

// `cam`: { az, el, moved }; `redraw()` draws it, `zoom(f)` zooms out by
// `f`, `reset()` fits.
export function orbit(canvas, cam, { redraw, zoom, reset }) {
  const turn = (daz, del) => {
    cam.az += daz;
    cam.el = Math.max(-90, Math.min(90, cam.el + del));
    cam.moved = true;
    redraw();
  };
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY, az: cam.az, el: cam.el };
    canvas.setPointerCapture(e.pointerId);
    canvas.focus({ preventScroll: true });
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    turn(drag.az - (e.clientX - drag.x) * DEG_PER_PX - cam.az,
      drag.el + (e.clientY - drag.y) * DEG_PER_PX - cam.el);
  });
  const end = () => { drag = null; };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    zoom(e.deltaY > 0 ? ZOOM_STEP : 1 / ZOOM_STEP);
  }, { passive: false });
  canvas.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const step = e.shiftKey ? 3 * KEY_STEP : KEY_STEP;
    // As dragging: the pointer right turns AZ down, down turns EL up.
    const keys = {
      ArrowLeft: () => turn(step, 0),
      ArrowRight: () => turn(-step, 0),
      ArrowUp: () => turn(0, step),
      ArrowDown: () => turn(0, -step),
      '+': () => zoom(1 / ZOOM_STEP),
      '=': () => zoom(1 / ZOOM_STEP),
      '-': () => zoom(ZOOM_STEP),
      '0': reset,
      Home: reset,
    };
    const act = keys[e.key];
    if (!act) return;
    e.preventDefault();
    act();
  });
}
