// Writes docs/benchmarks.md from the output of `npm run bench`:
//
//   npm run bench 2>&1 | tee bench.log && node scripts/bench-report.mjs bench.log
//
// The part above the history marker is regenerated: one section per `=== ...` block of the log
// (scripts/bench.sh prints one before adasculpt_bench and before each scripts/bench-*.sh); Google
// Benchmark's console table becomes a markdown table, markdown the scripts print stays as it is,
// other lines become a code block. Everything below the marker is kept as written (the measurement
// history, notes other documents link to). A new benchmark (a BENCHMARK in tests/bench/*.cpp or a
// scripts/bench-*.sh) shows up without a change here.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const out = path.join(root, 'docs', 'benchmarks.md');
const MARKER = '<!-- bench-report: everything below this line is kept as written -->';

const [logFile] = process.argv.slice(2);
if (!logFile) {
  console.error('usage: node scripts/bench-report.mjs BENCH_LOG   (the saved output of `npm run bench`)');
  process.exit(2);
}
const log = fs.readFileSync(logFile, 'utf8').replace(/\x1b\[[0-9;]*m/g, ''); // no terminal colours

// Sections: a line "=== title" starts one; lines before the first belong to "setup".
const sections = [];
let current = { title: 'setup', lines: [] };
for (const line of log.split('\n')) {
  const m = /^=== (.*)$/.exec(line);
  if (m) {
    sections.push(current);
    current = { title: m[1].trim(), lines: [] };
  } else {
    current.lines.push(line);
  }
}
sections.push(current);

// Google Benchmark console rows: "name   12.3 ms   12.1 ms   10 key=value...".
const GB_ROW = /^(\S+)\s+([\d.]+) (ns|us|ms|s)\s+([\d.]+) (ns|us|ms|s)\s+(\d+)\s*(.*)$/;
function googleBenchmark(lines) {
  const context = lines.filter((l) => /^(Run on|CPU Caches|Load Average|\*\*\*)/.test(l.trim()) || /^\s+L\d/.test(l));
  const rows = lines.map((l) => GB_ROW.exec(l)).filter(Boolean);
  if (!rows.length) return null;
  const md = ['| benchmark | time | CPU | iterations | counters |', '|---|---|---|---|---|'];
  for (const r of rows) md.push(`| \`${r[1]}\` | ${r[2]} ${r[3]} | ${r[4]} ${r[5]} | ${r[6]} | ${r[7].trim().replace(/\|/g, '\\|')} |`);
  return [...(context.length ? ['```', ...context.map((l) => l.trimEnd()), '```', ''] : []), ...md];
}

function passThrough(lines) {
  const md = [];
  let text = [];
  const flush = () => {
    while (text.length && !text[text.length - 1].trim()) text.pop();
    if (text.length) md.push('```', ...text, '```', '');
    text = [];
  };
  for (const l of lines) {
    if (l.startsWith('|')) {
      flush();
      md.push(l);
    } else if (md.length && md[md.length - 1].startsWith('|') && !l.trim()) {
      md.push('');
    } else if (l.trim() || text.length) {
      text.push(l.trimEnd());
    }
  }
  flush();
  return md;
}

const git = (...a) => { try { return execFileSync('git', a, { cwd: root, encoding: 'utf8' }).trim(); } catch { return '?'; } };
const body = [
  '# Benchmarks',
  '',
  `Produced by \`node scripts/bench-report.mjs\` from the output of \`npm run bench\` (scripts/bench.sh) at commit`,
  `${git('rev-parse', '--short', 'HEAD')}, ${new Date().toISOString().slice(0, 16).replace('T', ' ')} UTC, on ${os.cpus().length} cores ` +
  `(${os.cpus()[0]?.model?.trim() || 'unknown CPU'}), load average ${os.loadavg().map((x) => x.toFixed(1)).join(' / ')} when the report was written.`,
  'Wall-clock figures on a shared machine are noisy: compare medians of repeated runs, not single numbers.',
  'Regenerate: `npm run bench 2>&1 | tee bench.log && node scripts/bench-report.mjs bench.log`.',
  'Frame-time, undo/scaling and robustness studies have their own pages: [frame-time.md](frame-time.md),',
  '[undo-and-scaling.md](undo-and-scaling.md), [robustness.md](robustness.md).',
  '',
];
for (const s of sections) {
  // npm's noise and progress lines ("  bunny draw done") are left out.
  const lines = s.lines.filter((l) => !/^npm (warn|notice)/.test(l) && !/^\s+\S.* done$/.test(l));
  if (!lines.some((l) => l.trim())) continue;
  if (s.title === 'setup') continue; // the build's own output
  body.push(`## \`${s.title}\``, '');
  const gb = /adasculpt_bench/.test(s.title) ? googleBenchmark(lines) : null;
  body.push(...(gb || passThrough(lines)), '');
}

const previous = fs.existsSync(out) ? fs.readFileSync(out, 'utf8') : '';
const kept = previous.includes(MARKER) ? previous.slice(previous.indexOf(MARKER) + MARKER.length) : '\n';
fs.mkdirSync(path.dirname(out), { recursive: true });
fs.writeFileSync(out, `${body.join('\n').replace(/\n{3,}/g, '\n\n')}\n${MARKER}${kept}`);
console.log(`wrote ${path.relative(root, out)} (${sections.length - 1} sections from ${logFile})`);
