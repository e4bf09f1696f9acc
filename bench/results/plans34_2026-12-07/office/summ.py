import json, subprocess, statistics as st, sys, os, re
os.chdir('/tmp/plans34/office')
ref = sys.argv[1]
rows = []
for b in sys.argv[2:]:
    if not os.path.exists(b + '.done'): continue
    t = open(b + '.time').read()
    cpu = float(re.search(r'User time \(seconds\): ([\d.]+)', t).group(1)) + float(re.search(r'System time \(seconds\): ([\d.]+)', t).group(1))
    rss = int(re.search(r'Maximum resident set size \(kbytes\): (\d+)', t).group(1)) / 1024
    r = subprocess.run(['/work/wt-plans34/build/apps/cpgi', 'compare-light', b, ref, '--json', '--scene', 'office.glb'], capture_output=True, text=True)
    if r.returncode: print(b, r.stderr); continue
    d = json.loads(r.stdout)
    json.dump(d, open('cmp-%s-%s.json' % (b, ref), 'w'), indent=1)
    cs = [c for c in d['cells'] if c.get('texels', 0) > 0]
    err = sorted((abs(c['ratio_of_means'] - 1), c['name'], c['ratio_of_means'] - 1) for c in cs)
    rm = sorted((c['rel_rmse_without_noise'], c['name']) for c in cs)
    se = st.median(c['ratio_error'] for c in cs)
    rep = json.load(open(b + '/report.json'))
    tm = rep['timings']
    off3 = sum(1 for e in err if e[0] > 0.03)
    rows.append((b, cpu, rss, len(cs), 100*st.median(e[0] for e in err), 100*err[int(0.9*len(err))][0], '%+.1f (%s)' % (100*err[-1][2], err[-1][1]), off3, 100*st.median(x[0] for x in rm), 100*rm[int(0.9*len(rm))][0], 100*se, rep['shots'], rep['atlas']['width']*0 + rep['texels'], rep.get('solve_texels'), rep['backend'], rep.get('indirect_solver'), {k: round(v) for k, v in tm.items() if v > 5}))
for r in rows:
    print('| %s | %.0f | %.0f | %d | %.1f / %.1f / %s | %d | %.1f / %.1f | %.1f | %d | %d / %s | %s, %s | %s |' % r)
