// Runs the script of a `braun plot -o FILE.html` page against a stand-in
// for the DOM (node, no browser): node page_check.js FILE.html
// Checks that exactly one configuration shows at a time, that playing
// advances in simulated time at the chosen speed and wraps around, that
// the slider shows the frame it points at and pauses, and that the button
// toggles play. Prints "ok - ..." / "not ok - ..." lines; exit 1 on failure.
'use strict';
const fs = require('fs');
const html = fs.readFileSync(process.argv[2], 'utf8');
let failed = 0;
function check(name, cond) { console.log((cond ? 'ok - ' : 'not ok - ') + name); if (!cond) failed++; }

const scripts = html.match(/<script>([\s\S]*?)<\/script>/g) || [];
check('one inline script', scripts.length === 1);
const code = scripts.length ? scripts[0].replace(/^<script>|<\/script>$/g, '') : '';
const times = [...html.matchAll(/<g data-t="([^"]+)" style="display:none">/g)].map(m => parseFloat(m[1]));
check('frames carry their times (' + times.length + ')', times.length > 1);

function el() { return { style: {}, textContent: '', value: 0 }; }
const frames = times.map(t => { const e = el(); e.style.display = 'none'; e.getAttribute = () => String(t); return e; });
const ids = { frames: { children: frames }, slider: el(), now: el(), play: el(), speed: el() };
ids.speed.value = '1';
let pending = null;
const sandbox = {
  document: { getElementById: id => ids[id] },
  window: { requestAnimationFrame: f => { pending = f; } },
};
new Function('document', 'window', code)(sandbox.document, sandbox.window);
const shown = () => frames.map((f, i) => f.style.display === '' ? i : -1).filter(i => i >= 0);
check('the first frame shows at the start', shown().length === 1 && shown()[0] === 0);
// The readout's digits tell the frames apart (docs/cli.md): at least 3,
// one more than the smallest spacing needs, at most 12.
let dig = 3;
for (let i = 1; i < times.length; i++) { const g = times[i] - times[i - 1];
  if (g > 0) dig = Math.max(dig, Math.min(12, Math.ceil(-Math.log10(g)) + 1)); }
check('the time reads t = ' + times[0].toFixed(dig) + ' s', ids.now.textContent === 't = ' + times[0].toFixed(dig) + ' s');
// Play for half the run at speed 1: the frame shown is the last one at or before that time.
const span = times[times.length - 1] - times[0];
let ts = 1000;
pending(ts);
const half = times[0] + span / 2;
for (let k = 0; k < 50; k++) { ts += span / 2 * 1000 / 50; pending(ts); }
const want = times.filter(t => t <= half + 1e-9).length - 1;
check('after ' + (span / 2).toFixed(3) + ' s of play, one frame shows: the last before t = ' + half.toFixed(3),
      shown().length === 1 && Math.abs(shown()[0] - want) <= 1);
check('the slider follows the animation', Math.abs(ids.slider.value - want) <= 1);
// Past the end it starts again.
for (let k = 0; k < 30; k++) { ts += span * 1000 / 30; pending(ts); }
check('it loops', shown().length === 1);
// The slider picks a frame and pauses.
ids.slider.value = String(Math.floor(times.length / 3));
ids.slider.oninput();
const picked = Math.floor(times.length / 3);
check('the slider shows frame ' + picked, shown().length === 1 && shown()[0] === picked);
check('moving the slider pauses', ids.play.textContent === 'Play');
for (let k = 0; k < 10; k++) { ts += 100; pending(ts); }
check('paused: the frame stays', shown()[0] === picked);
ids.play.onclick();
check('the button plays again', ids.play.textContent === 'Pause');
ids.speed.value = '10';
const before = shown()[0];
ts += 16; pending(ts); ts += 100; pending(ts);
const step = times.length > 1 ? (times[times.length - 1] - times[0]) / (times.length - 1) : 1;
check('at speed 10, 0.1 s of play moves about 1 s of simulated time',
      Math.abs((times[shown()[0]] - times[before]) - 1.0) <= 2 * step + 0.2 || span < 1.5);
process.exit(failed ? 1 : 0);
