#!/usr/bin/env python3
# Usage: stlc serve --port 0 (note the URL); chromedriver --port=9516; then
#   python3 benches/serve_latency.py http://127.0.0.1:9516 URL 21 examples/2dtree.od examples/fig9.od examples/holes.od
# (docs/serve.md, Latency). Needs chromium and chromium-driver.
# Keystroke-to-picture latency of stlc serve in headless Chromium, through
# chromedriver's WebDriver HTTP API: for each example, N edits (a `#`, an
# empty comment, added at the end of the text and removed again), each timed
# by the page from the input event to the redrawn picture
# ((window.stlc.state || window.stlc).timings).
import json, sys, time, urllib.request, statistics, subprocess, os
drv, url, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
def call(method, path, body=None):
    req = urllib.request.Request(drv + path, method=method, data=None if body is None else json.dumps(body).encode(), headers={'Content-Type': 'application/json'})
    return json.load(urllib.request.urlopen(req))['value']
caps = {'capabilities': {'alwaysMatch': {'goog:chromeOptions': {'binary': '/usr/bin/chromium', 'args': ['--headless', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--window-size=1280,860', '--user-data-dir=/tmp/lat-profile']}}}}
sid = call('POST', '/session', caps)['sessionId']
def js(script):
    return call('POST', f'/session/{sid}/execute/sync', {'script': script, 'args': []})
call('POST', f'/session/{sid}/url', {'url': url})
time.sleep(2)
for name in sys.argv[4:]:
    text = open(name).read()
    js("document.getElementById('source').value = %s; document.getElementById('source').dispatchEvent(new Event('input')); return 0;" % json.dumps(text))
    time.sleep(3)
    js("(window.stlc.state || window.stlc).timings.length = 0; return 0;")
    for i in range(runs):
        edit = text + ('#' if i % 2 == 0 else '')
        js("document.getElementById('source').value = %s; document.getElementById('source').dispatchEvent(new Event('input')); return 0;" % json.dumps(edit))
        for _ in range(200):
            n = js("return (window.stlc.state || window.stlc).timings.length")
            if n > i: break
            time.sleep(0.01)
    t = js("return (window.stlc.state || window.stlc).timings")
    stems = int(js("return (window.stlc.state || window.stlc).answer.stems"))
    print(f"{os.path.basename(name)}: stems {stems}, median {statistics.median(t):.0f} ms, min {min(t):.0f}, max {max(t):.0f} over {len(t)}")
call('DELETE', f'/session/{sid}')
