#!/usr/bin/env python3
# The light lane under heavy load, and the memory given back after it
# (issue 36, problems 4 and 5; docs/serve.md, "Bounded work").
#
#   python3 benches/light_lane.py [BINARY] [HEAVY_CLIENTS] [SECONDS]
#   (defaults: target/release/stlc, 120, 60; build it first with
#   cargo build --release)
#
# Starts `stlc serve FILE --port 0`, measures its idle resident size, then
# runs HEAVY_CLIENTS clients that each send a heavy render (a stochastic
# .lsys at depth 12, many seconds of work) again and again (after a 503,
# they wait its Retry-After), while one light client asks `GET /api/file`
# and renders fig9.od in turn. After SECONDS the heavy clients stop, and
# the server idles 30 s. Prints the light answers' p50, p99 and maximum,
# what the heavy clients were answered, and the resident size fresh, at
# its peak and idle after the load; then 8 clients grow a 200,000-stem
# tree 3 times each, and the resident size is printed at its peak and 20 s
# after. Bounded: SECONDS + about 2 minutes.
import http.client, json, os, statistics, subprocess, sys, tempfile, threading, time

binary = sys.argv[1] if len(sys.argv) > 1 else 'target/release/stlc'
clients = int(sys.argv[2]) if len(sys.argv) > 2 else 120
seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 60
HEAVY = json.dumps({"source": "axiom FX\nrule X (0.5) -> XXXXX+\nrule X (0.5) -> XXXXX-\nangle 30\n", "kind": "lsys", "depth": 12})
LIGHT = json.dumps({"source": open('examples/fig9.od').read()})

tmp = tempfile.mkdtemp()
path = os.path.join(tmp, 'tree.od')
with open(path, 'w') as f:
    f.write(open('examples/fig9.od').read())
server = subprocess.Popen([binary, 'serve', path, '--port', '0'], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
url = server.stdout.readline().strip()
addr, token = url[len('http://'):].split('/#token=')
host, port = addr.split(':')

def rss_kb():
    for line in open(f'/proc/{server.pid}/status'):
        if line.startswith('VmRSS:'):
            return int(line.split()[1])

def ask(method, path, body=None, timeout=120):
    c = http.client.HTTPConnection(host, int(port), timeout=timeout)
    c.request(method, path, body=body, headers={'X-Stlc-Token': token, 'Content-Type': 'application/json'})
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, r.getheader('Retry-After'), data

time.sleep(1)
ask('POST', '/api/render', LIGHT)
time.sleep(2)
fresh = rss_kb()
stop = time.time() + seconds
counts = {}
lock = threading.Lock()
peak = [fresh]

def heavy():
    while time.time() < stop:
        try:
            status, retry, _ = ask('POST', '/api/render', HEAVY, timeout=stop - time.time() + 5)
        except Exception:
            status, retry = 'dropped', None
        with lock:
            counts[status] = counts.get(status, 0) + 1
        if retry:
            time.sleep(min(float(retry), max(0, stop - time.time())))

threads = [threading.Thread(target=heavy, daemon=True) for _ in range(clients)]
for t in threads:
    t.start()
time.sleep(2)
light = []
while time.time() < stop:
    for method, p, body in (('GET', '/api/file', None), ('POST', '/api/render', LIGHT)):
        t0 = time.time()
        status, _, _ = ask(method, p, body)
        light.append(time.time() - t0)
        assert status == 200, (p, status)
    peak[0] = max(peak[0], rss_kb())
    time.sleep(0.1)
for t in threads:
    t.join(timeout=60)
# Idle: every heavy work stopped (time budget, abandoned) and given back.
idle = []
for _ in range(30):
    time.sleep(1)
    idle.append(rss_kb())
# Memory: 8 clients grow benches/bigtree.od (200,000 stems) 3 times each
# at once, then the server idles 20 s.
BIG = json.dumps({"source": open('benches/bigtree.od').read()})
def big():
    for _ in range(3):
        ask('POST', '/api/render', BIG)
before_big = rss_kb()
bigs = [threading.Thread(target=big) for _ in range(8)]
for t in bigs:
    t.start()
big_peak = before_big
while any(t.is_alive() for t in bigs):
    big_peak = max(big_peak, rss_kb())
    time.sleep(0.2)
time.sleep(20)
big_idle = rss_kb()
light.sort()
q = lambda p: light[min(len(light) - 1, int(p * len(light)))]
print(f"light lane, {clients} heavy clients, {seconds:.0f} s: {len(light)} light answers, "
      f"p50 {q(0.5)*1000:.0f} ms, p99 {q(0.99)*1000:.0f} ms, max {light[-1]*1000:.0f} ms")
print(f"heavy answers: {dict(sorted((str(k), v) for k, v in counts.items()))}")
print(f"resident: fresh {fresh/1024:.0f} MB, peak {peak[0]/1024:.0f} MB, idle after "
      f"{idle[-1]/1024:.0f} MB (min over 30 s {min(idle)/1024:.0f} MB)")
print(f"then 8 x 3 growths of 200,000 stems: peak {big_peak/1024:.0f} MB, idle 20 s after "
      f"{big_idle/1024:.0f} MB ({(big_idle - fresh)/1024:.0f} MB above fresh)")
server.terminate()
server.wait()
