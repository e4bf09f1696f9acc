// report.html's numbers: per-cell table, portals, timings by stage and every parameter of report.json.
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
  return String(text).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
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
    .map(([stage, t]) => `<tr><td>${escapeHtml(stage)}</td><td class="num">${formatNumber(t)}</td>
      <td><span class="bar" style="width:${Math.max(0.5, (100 * t) / total).toFixed(1)}%"></span></td></tr>`)
    .join('');
  return section(`Timings (${formatNumber(total)} s in all)`,
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

export function buildPanels(element, data) {
  element.innerHTML = [cellsSection(data), portalsSection(data), timingsSection(data.report),
    warningsSection(data.report), parametersSection(data.report)].join('');
}
