import json, re, statistics as st, os
os.chdir('/tmp/plans34/office')
label = {'global': 'global (default: auto → GL context, lamps and interreflection by rays)', 'cells': 'cells, the scene\'s own (binned, default backend)', 'cells-auto': 'cells, `--cells auto`', 'cells-rays': 'cells, `--backend rays`', 'shared': 'both bakes\' common part (`--max-shots 1 --no-ambient`, global)'}
for b in ['global', 'cells', 'cells-auto', 'cells-rays']:
    if not os.path.exists('cmp-%s-reference4.json' % b): continue
    t = open(b + '.time').read()
    cpu = float(re.search(r'User time \(seconds\): ([\d.]+)', t).group(1)) + float(re.search(r'System time \(seconds\): ([\d.]+)', t).group(1))
    rss = int(re.search(r'Maximum resident set size \(kbytes\): (\d+)', t).group(1)) / 1024
    d = json.load(open('cmp-%s-reference4.json' % b))
    cs = d['cells']
    err = sorted((abs(c['ratio_of_means'] - 1), c['name'], c['ratio_of_means'] - 1) for c in cs)
    rm = sorted(c['rel_rmse_without_noise'] for c in cs)
    rep = json.load(open(b + '/report.json'))
    print('| %s | %.0f | %.0f | %d | %d | %.1f / %.1f / %+.1f (%s) | %.1f / %.1f |' % (label[b], cpu, rss, rep['shots'], sum(e[0] > 0.03 for e in err), 100*st.median(e[0] for e in err), 100*err[int(0.9*len(err))][0], 100*err[-1][2], err[-1][1], 100*st.median(rm), 100*rm[int(0.9*len(rm))]))
