// Screenshot of a view page for the docs: node screenshot.mjs VIEW_HTML OUT_PNG T X0_M PX_PER_M
// COLOUR [SELECT_ID]. Same browser and profile set-up as the tests (lib.mjs); fails on a console
// error or a network request.
import { openView } from './lib.mjs';

const [file, out, t, x0, ppm, colour, select] = process.argv.slice(2);
if (!colour) {
  console.error('usage: node screenshot.mjs VIEW_HTML OUT_PNG T X0_M PX_PER_M COLOUR [SELECT_ID]');
  process.exit(2);
}
const v = await openView(file, { width: 1400, height: 720 });
await v.page.evaluate(([t, x0, ppm, colour, sel]) => {
  const V = window.__platoonsimView;
  V.setColour(colour);
  V.setTime(t);
  V.setView(x0, ppm);
  if (sel !== undefined) V.select(sel);
}, [Number(t), Number(x0), Number(ppm), colour, select === undefined ? undefined : Number(select)]);
await v.page.screenshot({ path: out });
await v.context.close();
if (v.errors.length || v.requests.length) {
  console.error('errors:', v.errors, 'requests:', v.requests);
  process.exit(1);
}
console.log(out);
