// A WebSocket client for the service tests: sends the messages of a file (one per line, sent as
// text exactly as written, so malformed JSON can be tested) one at a time, waiting for each answer
// (the JSON header, and the image after a 200), and writes the headers to OUTDIR/replies.jsonl and
// the images to OUTDIR/<n>.<ext> (n: the line number from 0).
// Usage: node ws_requests.mjs WS_URL MESSAGES_FILE OUTDIR [--timeout SECONDS]
// Exit: 0 all answered; 2 connection failed (3: the handshake was refused, status printed); 1 timeout.
import fs from 'node:fs';
import path from 'node:path';
import WebSocket from 'ws';

const [url, file, outdir, ...rest] = process.argv.slice(2);
const timeoutS = rest[0] === '--timeout' ? Number(rest[1]) : 60;
const lines = fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.trim() !== '');
fs.mkdirSync(outdir, { recursive: true });
const replies = fs.createWriteStream(path.join(outdir, 'replies.jsonl'));

const ws = new WebSocket(url);
let timer = setTimeout(() => { console.error(`no answer within ${timeoutS} s`); process.exit(1); }, timeoutS * 1000);
ws.on('unexpected-response', (req, res) => {
  console.log(`handshake refused: HTTP ${res.statusCode}`);
  process.exit(3);
});
ws.on('error', (e) => { console.error(`WebSocket error: ${e.message}`); process.exit(2); });

let n = 0;
let header = null;
function next() {
  if (n >= lines.length) { ws.close(); return; }
  clearTimeout(timer);
  timer = setTimeout(() => { console.error(`message ${n}: no answer within ${timeoutS} s`); process.exit(1); }, timeoutS * 1000);
  ws.send(lines[n]);
}
ws.on('open', next);
ws.on('message', (data, isBinary) => {
  if (!isBinary) {
    header = JSON.parse(data.toString());
    replies.write(JSON.stringify(header) + '\n');
    if (header.dropped) return;  // (one request at a time: should not happen)
    if (header.status !== 200) { n++; header = null; next(); }
    return;
  }
  const ext = (header && header.content_type === 'image/jpeg') ? 'jpg' : 'png';
  fs.writeFileSync(path.join(outdir, `${n}.${ext}`), data);
  n++; header = null; next();
});
ws.on('close', () => {
  clearTimeout(timer);
  replies.end(() => process.exit(n >= lines.length ? 0 : 2));
});
