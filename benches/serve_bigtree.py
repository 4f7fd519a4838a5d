#!/usr/bin/env python3
# Usage: python3 benches/serve_bigtree.py RUNS FILE.od STLC [STLC...]
#   e.g. python3 benches/serve_bigtree.py 11 benches/bigtree.od /tmp/stlc-before target/release/stlc
# (docs/serve.md, "Big trees"; docs/performance.md). Needs chromium and
# chromium-driver.
#
# Edit to picture in headless Chromium for a big grown tree, for each stlc
# binary in turn (rounds alternate between them: A, B, A, B...), each
# serving FILE with `stlc serve --port 0` under /usr/bin/time -v (peak
# memory). Each edit adds or removes a `#` at the end of the text (an
# empty comment: the same tree) and is timed by the page's own clock:
#   edit     the input event (state.editedAt; the 40 ms debounce follows)
#   server   request sent to first byte of the answer (Resource Timing):
#            the server's own time
#   page     first byte to the picture drawn: the answer's transfer,
#            decoding and drawing (a big tree's canvas finished, if the
#            page has one) and then the frame that shows it
#   total    the input event to the picture drawn
#   stall    the longest main-thread task from the edit to the picture
#            (PerformanceObserver 'longtask': tasks over 50 ms; 0 = none)
# Also the server alone: POST /api/render from Python (no browser), with
# the JSON and the compact Accept header, median of RUNS.
import json, os, re, shutil, statistics, subprocess, sys, tempfile, time, urllib.request

runs, od, bins = int(sys.argv[1]), sys.argv[2], sys.argv[3:]
text = open(od).read()
tmp = tempfile.mkdtemp(prefix='bigtree-bench-')


def start_server(binary):
    out = open(os.path.join(tmp, f'serve-{len(os.listdir(tmp))}.txt'), 'w+')
    p = subprocess.Popen(['/usr/bin/time', '-v', binary, 'serve', '--port', '0', od],
                         stdout=subprocess.PIPE, stderr=out, text=True, start_new_session=True)
    url = p.stdout.readline().strip()
    return p, url, out


def peak_kb(out):
    out.seek(0)
    m = re.search(r'Maximum resident set size \(kbytes\): (\d+)', out.read())
    return int(m.group(1)) if m else None


def server_alone(url, accept):
    base, token = url.split('/?token=')
    body = json.dumps({'source': text, 'kind': 'od'}).encode()
    times, size = [], 0
    for _ in range(runs):
        req = urllib.request.Request(base + '/api/render', data=body, method='POST', headers={
            'Content-Type': 'application/json', 'X-Stlc-Token': token, 'Accept': accept})
        t = time.perf_counter()
        size = len(urllib.request.urlopen(req).read())
        times.append((time.perf_counter() - t) * 1000)
    return statistics.median(times), size


drv = subprocess.Popen(['chromedriver', '--port=9517'], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       start_new_session=True)
time.sleep(1)
DRV = 'http://127.0.0.1:9517'


def call(method, path, body=None):
    req = urllib.request.Request(DRV + path, method=method, data=None if body is None else json.dumps(body).encode(),
                                 headers={'Content-Type': 'application/json'})
    return json.load(urllib.request.urlopen(req))['value']


# Installed in the page before the edits: the longtask observer, and a hook
# on the view's draw that notes when each picture is on the screen.
HOOK = """
window.__long = [];
new PerformanceObserver((l) => { for (const e of l.getEntries()) window.__long.push([e.startTime, e.duration]); })
  .observe({ type: 'longtask', buffered: true });
window.__done = [];
const v = window.stlc.view, orig = v.draw;
v.draw = function () {
  orig.apply(this, arguments);
  const answered = performance.now();
  const t = window.stlc.view.tree;
  const p = t && t.settled ? t.settled() : Promise.resolve();
  p.then(() => requestAnimationFrame(() => setTimeout(() => window.__done.push([answered, performance.now()]), 0)));
};
return 0;
"""

SET = "document.getElementById('source').value = %s; document.getElementById('source').dispatchEvent(new Event('input')); return 0;"

MEASURE = """
const s = window.stlc.state, [answered, done] = window.__done[window.__done.length - 1];
const r = performance.getEntriesByType('resource').filter((e) => e.name.endsWith('/api/render')).pop();
const stall = window.__long.filter(([t, d]) => t + d >= s.editedAt && t <= done).reduce((m, [, d]) => Math.max(m, d), 0);
return { edit: s.editedAt, server: r.responseStart - r.requestStart, page: done - r.responseStart, transfer: r.responseEnd - r.responseStart,
         total: done - s.editedAt, stall, answered: answered - r.responseStart, bytes: r.encodedBodySize,
         stems: s.answer.stems };
"""

servers = [start_server(b) for b in bins]
results = {b: [] for b in bins}
alone = {}
try:
    for b, (_, url, _) in zip(bins, servers):
        alone[b] = (server_alone(url, 'application/json'), server_alone(url, 'application/x-stlc-render'))
    for rnd in range(2):
        for b, (_, url, _) in zip(bins, servers):
            caps = {'capabilities': {'alwaysMatch': {'goog:chromeOptions': {'binary': '/usr/bin/chromium', 'args': [
                '--headless', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--window-size=1280,860',
                f'--user-data-dir={tmp}/profile-{rnd}-{bins.index(b)}']}}}}
            sid = call('POST', '/session', caps)['sessionId']
            js = lambda script: call('POST', f'/session/{sid}/execute/sync', {'script': script, 'args': []})
            call('POST', f'/session/{sid}/url', {'url': url})
            for _ in range(300):
                if js("return !!(window.stlc && window.stlc.state.answer)"):
                    break
                time.sleep(0.05)
            js(HOOK)
            for i in range(runs):
                js(SET % json.dumps(text + ('#' if i % 2 == 0 else '')))
                for _ in range(3000):
                    if js("return window.__done.length") > i:
                        break
                    time.sleep(0.01)
                time.sleep(0.3)
                results[b].append(js(MEASURE))
            call('DELETE', f'/session/{sid}')
finally:
    drv.terminate()
    for p, _, _ in servers:
        os.killpg(p.pid, 2)
        p.wait()
med = lambda b, k: statistics.median(r[k] for r in results[b])
print(f"{os.path.basename(od)}: {results[bins[0]][0]['stems']} stems, {len(results[bins[0]])} edits each, medians (ms)")
print("| stlc | server alone, JSON | server alone, compact | server (page) | page: transfer | page: first byte to answer applied | page: first byte to picture | edit to picture | longest task | edits with a task over 50 ms | answer bytes | server peak MB |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for b, (_, _, out) in zip(bins, servers):
    (j, js_size), (c, c_size) = alone[b]
    stall = max(r['stall'] for r in results[b])
    kb = peak_kb(out)
    print(f"| {b} | {j:.0f} ({js_size/1e6:.1f} MB) | {c:.0f} ({c_size/1e6:.1f} MB) | {med(b, 'server'):.0f} | {med(b, 'transfer'):.0f} | {med(b, 'answered'):.0f} | "
          f"{med(b, 'page'):.0f} | {med(b, 'total'):.0f} | {med(b, 'stall'):.0f} (max {stall:.0f}) | "
          f"{sum(r['stall'] > 0 for r in results[b])} of {len(results[b])} | "
          f"{results[b][0]['bytes']/1e6:.1f} MB | {kb/1024 if kb else 0:.0f} |")
if os.environ.get('VERBOSE'):
    for b in bins:
        print(b, [(round(r['page']), round(r['stall'])) for r in results[b]])
shutil.rmtree(tmp, ignore_errors=True)
