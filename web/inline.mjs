// Makes the self-contained page: index.html with style.css, jumpcyl-single.js
// (the wasm inlined as base64) and app.js written into it. No network, one file.
//   node web/inline.mjs WEB_SRC_DIR OUT_DIR   ->  OUT_DIR/jumpcyl.html
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const [src, out] = process.argv.slice(2);
if (!src || !out) { console.error('usage: node web/inline.mjs WEB_SRC_DIR OUT_DIR'); process.exit(2); }
const read = (dir, name) => readFileSync(join(dir, name), 'utf8');
// A script's text cannot hold "</script" (it would end the element).
const safe = (js) => js.replace(/<\/script/gi, '<\\/script');
let html = read(src, 'index.html');
const replaceOnce = (from, to) => {
  const at = html.indexOf(from);
  if (at < 0 || html.indexOf(from, at + 1) >= 0) { console.error(`inline: '${from}' must occur once in index.html`); process.exit(1); }
  html = html.slice(0, at) + to + html.slice(at + from.length);
};
replaceOnce('<link rel="stylesheet" href="style.css">', `<style>\n${read(src, 'style.css')}</style>`);
replaceOnce('<script src="app.js"></script>',
  `<script>\n${safe(read(out, 'jumpcyl-single.js'))}\n</script>\n<script>\n${safe(read(src, 'app.js'))}</script>`);
writeFileSync(join(out, 'jumpcyl.html'), html);
