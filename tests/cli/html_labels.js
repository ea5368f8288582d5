// Runs the animation script of a braun plot .html under a minimal DOM and
// prints the time label of every frame, one per line.
const fs = require('fs');
const html = fs.readFileSync(process.argv[2], 'utf8');
const ts = [...html.matchAll(/<g data-t="([^"]*)"/g)].map(m => m[1]);
const script = html.match(/<script>([\s\S]*?)<\/script>/)[1];
const frames = ts.map(t => ({ style: {}, getAttribute: () => t }));
const els = { frames: { children: frames }, slider: {}, now: { textContent: '' }, play: {}, speed: { value: '1' } };
global.document = { getElementById: id => els[id] };
global.window = { requestAnimationFrame: () => 0 };
eval(script);
for (let j = 0; j < frames.length; j++) { els.slider.value = j; els.slider.oninput(); console.log(els.now.textContent); }
