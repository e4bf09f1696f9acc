// report.html's numbers: per-cell table, portals, the bench's speed against accuracy, timings by stage and
// every parameter of report.json.
// Plain DOM tables, built from the page's #cpgi-data (see viewer.js).

export function formatNumber(x) {
  if (typeof x !== 'number') return x === undefined || x === null ? '–' : String(x);
  if (!Number.isFinite(x)) return String(x);
  if (Number.isInteger(x) && Math.abs(x) < 1e9) return x.toLocaleString('en');
  const a = Math.abs(x);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return x.toExponential(2);
  return Number(x.toPrecision(3)).toString();
}

function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);
}

function table(id, columns, rows) {
  const head = columns.map((c) => `<th title="${escapeHtml(c.title || '')}">${escapeHtml(c.label)}</th>`).join('');
  const body = rows
    .map((r) => '<tr>' + columns.map((c) => {
      const v = c.value(r);
      return `<td class="${typeof v === 'number' ? 'num' : ''}">${escapeHtml(formatNumber(v))}</td>`;
    }).join('') + '</tr>')
    .join('');
  return `<table id="${id}"><thead><tr>${head}</tr></thead><tbody>${body}</tbody></table>`;
}

function section(title, html) {
  return `<section><h2>${escapeHtml(title)}</h2>${html}</section>`;
}

// Cells: what the lightmap holds per cell (computed by cpgi from the texels); for a cells bake, the energy
// bookkeeping of the solver (report.json's cell_energy); for a comparison, compare-light's error per cell
// (its "cells", the worst one marked).
function cellsSection(data) {
  const cells = data.cells || [];
  if (!cells.length) return '';
  const energy = new Map((data.report.cell_energy || []).map((c) => [c.name, c]));
  const columns = [{ label: 'cell', value: (c) => c.name }];
  if (cells.some((c) => c.texels !== undefined))
    columns.push(
      { label: 'texels', value: (c) => c.texels },
      { label: 'area m²', value: (c) => c.area_m2, title: 'surface area of its baked texels' },
      { label: 'mean B W/m²', value: (c) => (c.area_m2 > 0 ? c.power_w / c.area_m2 : undefined), title: 'area-weighted mean radiosity' },
      { label: 'leaving W', value: (c) => c.power_w, title: 'Σ B·A over its texels: the light leaving its surfaces' });
  // report.json's own per-cell list: cells.json's cells (a decomposition) or compare-light's figures.
  const listed = new Map((Array.isArray(data.report.cells) ? data.report.cells : []).map((c) => [c.name, c]));
  const compared = data.kind === 'comparison' ? listed : new Map();
  const decomposed = data.kind === 'comparison' ? new Map() : listed;
  if (compared.size) {
    const e = (key) => (c) => compared.get(c.name)?.[key];
    columns.push(
      { label: 'worst', value: (c) => (c.name === data.report.worst_cell ? 'worst' : ''), title: 'ratio of means farthest from 1 (compare-light)' },
      { label: 'compared texels', value: e('texels') },
      { label: 'rel. RMSE', value: e('rel_rmse'), title: 'against the reference, normalised by the cell\'s own reference' },
      { label: 'ratio of means', value: e('ratio_of_means'), title: 'mean B of A / mean B of the reference' },
      { label: '± ratio', value: e('ratio_error'), title: 'standard error of the ratio of means' },
      { label: 'reference noise', value: e('reference_noise') });
  }
  if (decomposed.size) {
    const d = (key) => (c) => decomposed.get(c.name)?.[key];
    columns.push(
      { label: 'volume m³', value: d('volume_m3') },
      { label: 'voxels', value: d('voxels') },
      { label: 'triangles', value: d('triangles') },
      { label: 'peak m', value: d('peak_m'), title: 'largest distance to the geometry inside the cell' },
      { label: 'portals', value: (c) => decomposed.get(c.name)?.portals?.length });
  }
  if (energy.size) {
    const e = (key) => (c) => energy.get(c.name)?.[key];
    columns.push(
      { label: 'emitted W', value: e('emitted_w') },
      { label: 'received W', value: e('received_w'), title: 'through its portals' },
      { label: 'absorbed W', value: e('absorbed_w') },
      { label: 'sent W', value: e('sent_w'), title: 'through its portals' },
      { label: 'unshot W', value: e('unshot_w') },
      { label: 'escaped W', value: e('escaped_w') },
      { label: 'solves', value: e('solves') },
      { label: 'shots', value: e('shots') },
      { label: 'solve s', value: e('solve_seconds') });
  }
  if (columns.length === 1) return '';  // names only (a comparison): the legend of colour by cell has them
  return section('Cells', table('cells-table', columns, cells));
}

function portalsSection(data) {
  const portals = data.report.portal_energy || [];
  if (!portals.length) return '';
  return section('Portals: light carried', table('portals-table', [
    { label: 'portal', value: (p) => p.name },
    { label: 'A → B W', value: (p) => p.a_to_b_w },
    { label: 'B → A W', value: (p) => p.b_to_a_w },
  ], portals));
}

function timingsSection(report) {
  // bake: {stage: s}; reference: [{stage, seconds}]; decompose (cells.json): timings_s {stage: s, total}.
  const raw = report.timings || report.timings_s || {};
  const timings = Array.isArray(raw) ? raw.map((t) => [t.stage, t.seconds])
    : Object.entries(raw).filter(([stage]) => stage !== 'total');
  if (!timings.length) return '';
  const total = report.seconds || raw.total || timings.reduce((s, [, t]) => s + t, 0);
  const rows = timings
    .map(([stage, t]) => `<tr><td>${escapeHtml(stage)}</td><td class="num">${escapeHtml(formatNumber(t))}</td>
      <td><span class="bar" style="width:${Math.max(0.5, (100 * Number(t)) / Number(total) || 0).toFixed(1)}%"></span></td></tr>`)
    .join('');
  return section(`Timings (${escapeHtml(formatNumber(total))} s in all)`,
    `<table id="timings-table"><thead><tr><th>stage</th><th>s</th><th></th></tr></thead><tbody>${rows}</tbody></table>`);
}

// Every other value of report.json, nested objects flattened as a.b.
function parametersSection(report) {
  const skip = new Set(['timings', 'timings_s', 'cell_energy', 'portal_energy', 'warnings', 'views']);
  const rows = [];
  const walk = (prefix, value) => {
    if (value && typeof value === 'object' && !Array.isArray(value)) {
      for (const [k, v] of Object.entries(value)) walk(prefix ? `${prefix}.${k}` : k, v);
    } else if (Array.isArray(value)) {
      if (!value.some((v) => v && typeof v === 'object')) rows.push([prefix, value.join(', ')]);  // tables: elsewhere
    } else {
      rows.push([prefix, value]);
    }
  };
  for (const [k, v] of Object.entries(report)) if (!skip.has(k)) walk(k, v);
  const body = rows.map(([k, v]) => `<tr><td>${escapeHtml(k)}</td><td class="${typeof v === 'number' ? 'num' : ''}">${escapeHtml(formatNumber(v))}</td></tr>`).join('');
  return section('Parameters and results (report.json)', `<table id="parameters-table"><tbody>${body}</tbody></table>`);
}

function warningsSection(report) {
  const warnings = report.warnings || [];
  if (!warnings.length) return '';
  return section('Warnings', '<ul>' + warnings.map((w) => `<li>${escapeHtml(w)}</li>`).join('') + '</ul>');
}

// Speed against accuracy (the rows of bench/speed_accuracy.py's results.json, given to compare-light with
// --bench): per scene, the relative RMSE without the lamps (with them when a row lacks it) against the
// whole bake's seconds, both logarithmic, one line per method through its atlas resolutions.
const METHOD_COLOURS = { 'global-hemicube': '#4e9bff', 'global-hemisphere': '#ff9e4a', 'cells-diffuse': '#5fd068',
  'cells-directional': '#ff5c5c' };
const benchError = (r) => (typeof r.rel_rmse_nonemissive === 'number' ? r.rel_rmse_nonemissive : r.rel_rmse);

function decades(values) {
  let lo = Math.floor(Math.min(...values)), hi = Math.ceil(Math.max(...values));
  if (hi === lo) hi = lo + 1;
  return [lo, hi];
}

function benchChart(scene, rows) {
  const W = 560, H = 300, left = 64, right = 150, top = 14, bottom = 40;
  const [x0, x1] = decades(rows.map((r) => Math.log10(r.seconds)));
  const [y0, y1] = decades(rows.map((r) => Math.log10(benchError(r))));
  const x = (s) => left + ((Math.log10(s) - x0) / (x1 - x0)) * (W - left - right);
  const y = (e) => H - bottom - ((Math.log10(e) - y0) / (y1 - y0)) * (H - top - bottom);
  const parts = [];
  for (let k = x0; k <= x1; ++k)
    parts.push(`<line x1="${x(10 ** k)}" x2="${x(10 ** k)}" y1="${top}" y2="${H - bottom}" class="grid"/>`,
      `<text x="${x(10 ** k)}" y="${H - bottom + 16}" text-anchor="middle">${escapeHtml(formatNumber(10 ** k))}</text>`);
  for (let k = y0; k <= y1; ++k)
    parts.push(`<line x1="${left}" x2="${W - right}" y1="${y(10 ** k)}" y2="${y(10 ** k)}" class="grid"/>`,
      `<text x="${left - 6}" y="${y(10 ** k) + 4}" text-anchor="end">${escapeHtml(formatNumber(10 ** k))}</text>`);
  parts.push(`<text x="${(left + W - right) / 2}" y="${H - 6}" text-anchor="middle">seconds (whole bake)</text>`,
    `<text transform="translate(14 ${(top + H - bottom) / 2}) rotate(-90)" text-anchor="middle">relative RMSE (lamps left out)</text>`);
  const methods = [...new Set(rows.map((r) => r.method))];
  methods.forEach((method, m) => {
    const colour = METHOD_COLOURS[method] || `hsl(${(m * 137) % 360} 70% 60%)`;
    const points = rows.filter((r) => r.method === method).sort((a, b) => a.seconds - b.seconds);
    parts.push(`<polyline class="method" data-method="${escapeHtml(method)}" fill="none" stroke="${colour}" stroke-width="2" points="${
      points.map((r) => `${x(r.seconds).toFixed(1)},${y(benchError(r)).toFixed(1)}`).join(' ')}"/>`);
    for (const r of points)
      parts.push(`<circle cx="${x(r.seconds).toFixed(1)}" cy="${y(benchError(r)).toFixed(1)}" r="4" fill="${colour}"><title>${
        escapeHtml(`${method}, ${r.resolution ?? ''}: ${formatNumber(r.seconds)} s, ${formatNumber(100 * benchError(r))} %`)}</title></circle>`,
      `<text x="${x(r.seconds) + 6}" y="${y(benchError(r)) - 6}" class="point">${escapeHtml(r.resolution ?? '')}</text>`);
    parts.push(`<rect x="${W - right + 12}" y="${top + 18 * m}" width="12" height="12" fill="${colour}"/>`,
      `<text x="${W - right + 30}" y="${top + 18 * m + 10}">${escapeHtml(method)}</text>`);
  });
  return `<figure class="bench-chart" data-scene="${escapeHtml(scene)}"><svg viewBox="0 0 ${W} ${H}" width="${W}" height="${H}">${
    parts.join('')}</svg><figcaption>${escapeHtml(scene)}</figcaption></figure>`;
}

function benchSection(data) {
  const rows = (Array.isArray(data.bench) ? data.bench : []).filter((r) => r && typeof r === 'object' &&
    r.seconds > 0 && benchError(r) > 0);
  if (!rows.length) return '';
  const scenes = [...new Set(rows.map((r) => String(r.scene ?? '')))];
  return section('Speed against accuracy (bench)',
    scenes.map((s) => benchChart(s, rows.filter((r) => String(r.scene ?? '') === s))).join(''));
}

export function buildPanels(element, data) {
  element.innerHTML = [cellsSection(data), portalsSection(data), benchSection(data), timingsSection(data.report),
    warningsSection(data.report), parametersSection(data.report)].join('');
}
