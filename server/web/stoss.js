// The page at / (docs/web.md): job list, submission, one job's live plots, summary, log and downloads.
// Plotting is Debian's dygraphs; this file only fetches the API (docs/api.md) and configures the plots.
'use strict';

const POLL_MS = 500;         // the job on show, while it runs
const LIST_POLL_MS = 1500;   // the job list
const FINAL = ['succeeded', 'failed', 'canceled'];

// ---- API access: the bearer token (asked once, kept in session storage) ------------------------------

function authHeaders() {
  const token = sessionStorage.getItem('stoss-token');
  return token ? { Authorization: 'Bearer ' + token } : {};
}

class Unauthorized extends Error {}

async function api(path, options = {}) {
  const response = await fetch(path, { ...options, headers: { ...authHeaders(), ...(options.headers || {}) } });
  if (response.status === 401) {
    askForToken(sessionStorage.getItem('stoss-token') ? 'that token was refused' : '');
    throw new Unauthorized();
  }
  return response;
}

async function apiJson(path) {
  const response = await api(path);
  return { status: response.status, body: await response.json() };
}

function askForToken(message) {
  document.getElementById('token-panel').hidden = false;
  document.getElementById('token-error').textContent = message;
}

document.getElementById('token-form').addEventListener('submit', (event) => {
  event.preventDefault();
  sessionStorage.setItem('stoss-token', document.getElementById('token-input').value.trim());
  document.getElementById('token-panel').hidden = true;
  start();
});

// ---- small DOM helpers --------------------------------------------------------------------------------

function el(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  node.append(...children);
  return node;
}

function number(value) {
  if (typeof value !== 'number') return String(value);
  if (Number.isInteger(value)) return String(value);
  return Math.abs(value) >= 1e-3 && Math.abs(value) < 1e5 ? value.toPrecision(4) : value.toExponential(3);
}

// The scene format has no units field (docs/scene.md): lengths, times, energies are in the scene's own units.
const UNITS = 'model units';

// Log-axis ticks (a dygraphs `ticker`): decades only (1e-11, 1e-10, …), every k-th one so that labels stay
// 30 px apart; where fewer than two decades fall inside, the 1-2-5 steps, then 1…9 (each label a distinct
// one-digit number); where fewer than two of those fall inside, the range's two ends.
function logTicks(min, max, pixels) {
  if (!(min > 0) || !(max > min)) return [];
  const low = Math.floor(Math.log10(min)), high = Math.ceil(Math.log10(max));
  const every = Math.ceil((high - low + 1) / Math.max(2, Math.floor(pixels / 30)));
  const ticks = (mantissas, step) => {
    const values = [];
    for (let e = low; e <= high; ++e) if (e % step === 0) for (const m of mantissas) values.push(m * 10 ** e);
    return values.filter((v) => v >= min && v <= max).map((v) => ({ v, label: logLabel(v) }));
  };
  for (const [mantissas, step] of [[[1], every], [[1, 2, 5], 1]]) {
    const found = ticks(mantissas, step);
    if (found.length >= 2) return found;
  }
  const dense = ticks([1, 2, 3, 4, 5, 6, 7, 8, 9], 1);
  return dense.length >= 2 ? dense : [min, max].map((v) => ({ v, label: Number(v.toPrecision(2)).toString() }));
}

// 1, 20, 0.005 as written; outside 1e-3 … 1e4 as 1e-11, 2e-5.
function logLabel(v) {
  const e = Math.floor(Math.log10(v) + 1e-9);
  const m = Math.round(v / 10 ** e);
  return e >= -3 && e <= 4 ? String(Number((m * 10 ** e).toPrecision(1))) : m + 'e' + e;
}

// The unit of a summary member, from its name.
function unitOf(key) {
  if (/_seconds$/.test(key)) return 's';
  if (/_mb$/.test(key)) return 'MB';
  if (/drift|_error/.test(key)) return 'relative';
  if (/iterations|steps|fallbacks|^step$|runs/.test(key)) return '';
  if (/energy|time|penetration/.test(key)) return UNITS;
  return '';
}

// What each plot's y axis measures (by plot id).
const Y_LABELS = { energy: 'energy (' + UNITS + ')', 'energy-error': 'relative error', 'momentum-error': 'momentum (' + UNITS + ')',
                   contact: 'count; penetration (' + UNITS + ')', newton: 'iterations', 'step-size': 'h (' + UNITS + ')', dissipation: 'energy (' + UNITS + ')',
                   'external-work': 'energy (' + UNITS + ')', 'reaction-force': 'force (' + UNITS + ')', 'contact-force': 'force (' + UNITS + ')' };

function duration(seconds) {
  if (seconds === null || seconds === undefined) return '';
  if (seconds < 90) return Math.round(seconds) + ' s';
  return Math.round(seconds / 60) + ' min';
}

function progressText(job, long) {
  const p = job.progress;
  const unit = job.kind === 'study' ? 'run' : 'step';
  const share = p.steps ? ` (${Math.floor((100 * p.step) / p.steps)} %)` : '';
  const time = long && job.kind === 'simulation' ? ` · t = ${number(p.time)} of ${number(p.end)}` : '';
  return (long ? unit + ' ' : '') + `${p.step}/${p.steps}${share}${time}`;
}

// ---- the job list ---------------------------------------------------------------------------------------

let listRequests = 0;  // an answer to an older request (before the filter changed) is dropped

async function refreshList() {
  const request = ++listRequests;
  const status = document.getElementById('status-filter').value;
  const { body } = await apiJson('/v1/jobs?limit=50' + (status ? '&status=' + status : ''));
  if (request !== listRequests) return;
  const rows = body.jobs.map((job) => {
    const row = el('tr', { 'data-id': job.id, 'data-status': job.status, class: job.id === shown.id ? 'selected' : '' },
      el('td', { class: 'status ' + job.status + (suspectReasons(job.summary) ? ' suspect' : ''), title: suspectReasons(job.summary) },
        job.status + (suspectReasons(job.summary) ? ' · suspect' : '')), el('td', {}, job.kind), el('td', {}, job.name || job.id),
      el('td', {}, progressText(job)), el('td', {}, duration(job.progress.eta_seconds)),
      el('td', { title: job.created }, job.created.slice(11, 19)));
    row.addEventListener('click', () => showJob(job.id));
    return row;
  });
  document.querySelector('#jobs tbody').replaceChildren(...rows);
}

document.getElementById('status-filter').addEventListener('change', () => refreshList());

// ---- submission: an example or a file, errors next to the field their JSON pointer names -------------

async function loadExamples() {
  const { body } = await apiJson('/v1/examples');
  const select = document.getElementById('example');
  select.replaceChildren(select.options[0]);
  for (const example of body.examples) {
    const option = el('option', { value: example.name }, example.name + ' — ' + example.title);
    option.scene = example.scene;
    select.append(option);
  }
}

document.getElementById('example').addEventListener('change', (event) => {
  const option = event.target.selectedOptions[0];
  if (option.scene) document.getElementById('scene-text').value = JSON.stringify(option.scene, null, 2);
});

document.getElementById('scene-file').addEventListener('change', async (event) => {
  const file = event.target.files[0];
  if (file) document.getElementById('scene-text').value = await file.text();
});

function escapePointer(key) {
  return String(key).replaceAll('~', '~0').replaceAll('/', '~1');
}

// The scene as nested fields, each labelled with its JSON pointer; short arrays of numbers stay on one line.
function fieldTree(value, pointer, key, fields) {
  const node = el('div', { class: 'field', 'data-pointer': pointer });
  fields.set(pointer, node);
  const label = key === undefined ? '' : key + ': ';
  const flat = Array.isArray(value) && value.every((v) => v === null || typeof v !== 'object' || Array.isArray(v) && v.every((w) => typeof w !== 'object'));
  if (value !== null && typeof value === 'object' && !flat) {
    node.append(el('span', { class: 'key' }, label));
    for (const [k, v] of Object.entries(value)) node.append(fieldTree(v, pointer + '/' + escapePointer(k), k, fields));
  } else {
    const text = JSON.stringify(value);
    node.append(el('span', { class: 'key' }, label), el('span', { class: 'value' }, text.length > 90 ? text.slice(0, 87) + '…' : text));
  }
  return node;
}

// The form's own error slot for `pointer` (the scene text for "", the study's steps and schemes).
function formSlot(pointer) {
  return [...document.querySelectorAll('#submit-form .field-error[data-pointer]')].find((s) => s.dataset.pointer === pointer);
}

// Puts each error next to the field its pointer names, or next to its nearest shown ancestor with the rest of
// the pointer in front of the message (a missing member is "required" next to the object that lacks it).
function showErrors(errors, scene, scenePrefix) {
  document.querySelectorAll('#submit-form .field-error[data-pointer]').forEach((span) => (span.textContent = ''));
  const fields = new Map();
  document.getElementById('scene-tree').replaceChildren(scene === undefined ? '' : fieldTree(scene, '', undefined, fields));
  document.getElementById('scene-fields').hidden = scene === undefined;
  for (const error of errors) {
    let pointer = error.pointer;
    let rest = '';
    const text = () => (rest ? rest + ': ' : '') + error.message;
    for (;;) {
      const slot = pointer !== '' && formSlot(pointer);
      if (slot) { slot.textContent += text() + ' '; break; }
      const field = pointer.startsWith(scenePrefix) && fields.get(pointer.slice(scenePrefix.length));
      if (field) {
        const anchor = field.querySelector(':scope > .value') || field.querySelector(':scope > .key');
        anchor.after(el('span', { class: 'field-error', 'data-error-for': error.pointer }, text()));
        break;
      }
      if (pointer === '') { formSlot('').textContent += error.pointer + ': ' + error.message + ' '; break; }
      const cut = pointer.lastIndexOf('/');
      rest = pointer.slice(cut + 1) + (rest ? '/' + rest : '');
      pointer = pointer.slice(0, cut);
    }
  }
}

// What a dry run or a submission found before the run: warnings (code, pointer, message) and the choices made.
function showBeforeRun(list, answer) {
  const items = (answer.warnings || []).map((w) =>
    el('li', { class: 'warning', 'data-code': w.code, 'data-pointer': w.pointer }, `warning ${w.pointer}: ${w.message}`));
  for (const c of answer.choices || []) items.push(el('li', { class: 'choice', 'data-pointer': c.pointer }, `${c.pointer}: ${c.value} (${c.reason})`));
  list.replaceChildren(...items);
}

function requestBody() {
  const text = document.getElementById('scene-text').value;
  if (!document.getElementById('as-study').checked) return { path: '/v1/jobs', text, prefix: '' };
  const steps = document.getElementById('study-steps').value.split(',').map((s) => Number(s.trim()));
  const schemes = [...document.querySelectorAll('#study-schemes input:checked')].map((box) => box.value);
  const repeat = Number(document.getElementById('study-repeat').value);
  const tolerancesText = document.getElementById('study-tolerances').value.trim();
  let scene;
  try { scene = JSON.parse(text); } catch (e) { return { path: '/v1/studies', text, prefix: '/scene' }; }
  const study = { scene, steps, schemes, repeat };
  if (tolerancesText) study.tolerances = tolerancesText.split(',').map((s) => Number(s.trim()));
  return { path: '/v1/studies', text: JSON.stringify(study), prefix: '/scene' };
}

async function submit(validateOnly) {
  const outcome = document.getElementById('submit-outcome');
  const request = requestBody();
  const path = validateOnly ? '/v1/validate' : request.path;
  const body = validateOnly ? document.getElementById('scene-text').value : request.text;
  const response = await api(path, { method: 'POST', body, headers: { 'Content-Type': 'application/json' } });
  const answer = await response.json();
  let scene;
  try { scene = JSON.parse(document.getElementById('scene-text').value); } catch (e) { scene = undefined; }
  showBeforeRun(document.getElementById('scene-warnings'), response.ok ? answer : {});
  if (response.ok) {
    showErrors([], undefined, '');
    outcome.className = 'ok';
    if (validateOnly) {
      const estimate = answer.estimates ? `; about ${duration(answer.estimates.wall_seconds) || '0 s'} to run` : '';
      const warned = answer.warnings.length ? `; ${answer.warnings.length} warning(s) below` : '';
      outcome.textContent = `valid: ${answer.effects.join(', ')}; ${answer.nodes} nodes, ${answer.steps} steps${estimate}${warned}`;
      return;
    }
    outcome.textContent = 'queued ' + answer.id;
    await refreshList();
    showJob(answer.id);
    return;
  }
  outcome.className = 'field-error';
  outcome.textContent = answer.detail;
  const errors = answer.errors || (answer.limits || []).map((l) => ({ pointer: '', message: `${l.name}: ${l.value} > ${l.limit}` }));
  showErrors(errors.length ? errors : [{ pointer: '', message: answer.detail }], scene, request.prefix);
}

document.getElementById('submit-form').addEventListener('submit', (event) => { event.preventDefault(); submit(false); });
document.getElementById('validate-button').addEventListener('click', () => submit(true));

// ---- one job: live plots (dygraphs configuration), summary, log, cancel, downloads --------------------

const norm = (v) => Math.hypot(...v);
const difference = (a, b) => a.map((x, i) => x - b[i]);
const positive = (v) => (v > 0 && Number.isFinite(v) ? v : null);   // log axes show no zeros

// Each plot: the series it needs, its labels, one row of values per step, dygraphs options.
const PLOTS = [
  { id: 'energy', title: 'Energy', needs: ['total_energy'], labels: ['total H', 'kinetic K', 'strain V'],
    row: (s, i) => [s.total_energy[i], s.kinetic_energy[i], s.strain_energy[i]] },
  // With loads or moving supports W enters, and the scale is max |H| so far, as energy_drift's (docs/results.md):
  // a loaded body may start at rest, H₀ = 0. Static load steps keep no energy between load levels: no plot.
  { id: 'energy-error', needs: ['total_energy'], labels: ['energy error'], logscale: true, dynamicOnly: true,
    title: (s) => ('external_work' in s ? 'Energy error |H − W − H₀| / max |H|' : 'Energy error |H − H₀| / |H₀|'),
    row: (s, i, first, state) => [positive(energyError(s, i, first, state))] },
  // Only where the system is free (no supports, no gravity: docs/results.md "Verdict"); elsewhere the
  // momenta change by the supports' and gravity's impulse, which is no error.
  { id: 'momentum-error', title: 'Momentum error ‖L − L₀‖, ‖J − J₀‖', needs: ['linear_momentum', 'angular_momentum'], freeOnly: true,
    labels: ['linear ‖L − L₀‖', 'angular ‖J − J₀‖'], logscale: true,
    row: (s, i, first) => [positive(norm(difference(s.linear_momentum[i], first.linear_momentum))),
                           positive(norm(difference(s.angular_momentum[i], first.angular_momentum)))] },
  { id: 'contact', title: 'Active contacts and max penetration', needs: ['active_contacts', 'max_penetration'],
    labels: ['active contacts', 'max penetration'], series: { 'max penetration': { axis: 'y2' } },
    row: (s, i) => [s.active_contacts[i], s.max_penetration[i]] },
  { id: 'newton', title: 'Newton iterations per step', needs: ['newton_iterations'], labels: ['Newton iterations'], stepPlot: true,
    row: (s, i) => [s.newton_iterations[i]] },
  // Only where steps are chosen by time.tolerance (docs/scene.md "Time"): with fixed steps h is time.step.
  { id: 'step-size', title: 'Step size h (chosen by time.tolerance)', needs: ['step_size'], adaptiveOnly: true,
    labels: ['step size h'], logscale: true, row: (s, i) => [positive(s.step_size[i])] },
  { id: 'dissipation', title: 'Dissipated energy (friction) and H + D', needs: ['dissipated_energy'],
    labels: ['dissipated D', 'H + D'], row: (s, i) => [s.dissipated_energy[i], s.total_energy[i] + s.dissipated_energy[i]] },
  // With loads or prescribed motion: the work done on the bodies, and H − W, what energy–momentum keeps.
  { id: 'external-work', title: 'External work W and H − W', needs: ['external_work', 'total_energy'],
    labels: ['external work W', 'H − W'], row: (s, i) => [s.external_work[i], s.total_energy[i] - s.external_work[i]] },
  // [S,k,3] series (docs/results.md): a line per item and component, the items numbered as the result
  // attributes boundary_entries and contact_pairs name them.
  { id: 'reaction-force', title: 'Reaction force of each boundary entry', needs: ['reaction_force'],
    labels: (s) => itemLabels(s.reaction_force[0], 'entry'), row: (s, i) => s.reaction_force[i].flat() },
  { id: 'contact-force', title: 'Contact force of each pair (master on slave)', needs: ['contact_force'],
    labels: (s) => itemLabels(s.contact_force[0], 'pair'), row: (s, i) => s.contact_force[i].flat() },
];

// |H − H₀| / |H₀|, or with external work |H − W − H₀| / max |H| over the rows plotted so far.
function energyError(s, i, first, state) {
  const H = s.total_energy[i];
  if (!('external_work' in s)) return Math.abs(H - first.total_energy) / (Math.abs(first.total_energy) || 1);
  state.largestEnergy = Math.max(state.largestEnergy || 0, Math.abs(H));
  return Math.abs(H - s.external_work[i] - first.total_energy) / (state.largestEnergy || 1);
}

// Labels of an [S,k,3] series' lines from one of its rows: "<word> <k> x", "<word> <k> y", "<word> <k> z".
function itemLabels(items, word) {
  return items.flatMap((_, k) => ['x', 'y', 'z'].map((c) => `${word} ${k} ${c}`));
}

let shown = { id: null };

function resetPlots(state) {
  document.getElementById('plots').replaceChildren();
  state.graphs = {};
  state.data = {};
  state.first = null;
  state.since = null;
}

function plotRows(state, series) {
  const count = series.time.length;
  if (!count) return;
  if (!state.first) {
    state.first = {};
    for (const [name, values] of Object.entries(series)) if (Array.isArray(values)) state.first[name] = values[0];
  }
  for (const plot of PLOTS) {
    if (!plot.needs.every((name) => name in series) || (plot.freeOnly && !state.free) || (plot.adaptiveOnly && !state.adaptive)
        || (plot.dynamicOnly && state.static)) continue;
    if (!state.graphs[plot.id]) {
      const box = el('div', { class: 'plot', id: 'plot-' + plot.id, 'data-points': '0' });
      const legend = el('div', { class: 'legend' });
      document.getElementById('plots').append(el('div', {}, box, legend));
      state.data[plot.id] = [];
      const labels = typeof plot.labels === 'function' ? plot.labels(series) : plot.labels;
      state.graphs[plot.id] = { box, legend, plot, labels, graph: null };
    }
    const data = state.data[plot.id];
    const entry = state.graphs[plot.id];
    for (let i = 0; i < count; ++i) data.push([series.time[i], ...plot.row(series, i, state.first, state)]);
    const y = plot.logscale ? { axisLabelWidth: 64, ticker: logTicks } : { axisLabelWidth: 64 };
    const title = typeof plot.title === 'function' ? plot.title(series) : plot.title;
    const options = { labels: ['t', ...entry.labels], title, xlabel: 't (' + UNITS + ')', ylabel: Y_LABELS[plot.id] || '',
                      logscale: !!plot.logscale, stepPlot: !!plot.stepPlot, series: plot.series || {}, connectSeparatedPoints: true,
                      legend: 'always', labelsDiv: entry.legend, height: 220, axes: { y, y2: { independentTicks: true, axisLabelWidth: 64 } } };
    if (entry.graph) entry.graph.updateOptions({ file: data });
    else entry.graph = new Dygraph(entry.box, data, options);
    entry.box.dataset.points = String(data.length);
  }
  state.since = series.step[count - 1];
}

async function pollSeries(job) {
  if (job.kind !== 'simulation' || job.status === 'queued') return true;
  if (shown.attempt !== job.attempt) { resetPlots(shown); shown.attempt = job.attempt; }
  shown.free = !job.effects.includes('dirichlet') && !job.effects.includes('gravity');
  shown.static = job.effects.includes('static');
  if (shown.adaptive === undefined) shown.adaptive = await stepsByTolerance(job);
  const since = shown.since === null ? '' : '?since=' + shown.since;
  const response = await api(`/v1/jobs/${job.id}/series${since}`);
  if (response.status === 409) return false;              // no step recorded yet
  const series = await response.json();
  plotRows(shown, series);
  if (series.summary) showSummary(series.summary, job.status === 'running' ? 'so far' : '');
  return series.completed !== false || FINAL.includes(job.status);
}

// Whether the job's steps are chosen by time.tolerance (its scene's time, read once per job shown).
async function stepsByTolerance(job) {
  const { status, body } = await apiJson(job.links.scene);
  return status === 200 && !!body.time && typeof body.time.tolerance === 'number';
}

// The failed checks of a suspect run, in words (docs/results.md "Verdict"); '' for an ok run.
function suspectReasons(summary) {
  if (!summary || summary.verdict !== 'suspect') return '';
  return 'suspect: ' + (summary.checks || []).filter((c) => !c.passed)
    .map((c) => `${c.name} ${number(c.value)} exceeds ${number(c.bound)}`).join('; ');
}

// A running job's summary has verdict null: the checks judge the whole run (docs/api.md, "Results": GET …/series).
const VERDICT_PENDING = 'made when the run ends';

// Figures the job's summary carries that say nothing about this run (docs/web.md): momentum drift where
// supports or gravity act (the impulse balance check stands in), energy drift of static load steps.
function meaningless(key) {
  return (!shown.free && (key === 'linear_momentum_drift' || key === 'angular_momentum_drift'))
    || (shown.static && key === 'energy_drift');
}

function showSummary(summary, note) {
  const text = (key, value) => typeof value === 'number' ? number(value)
    : key === 'verdict' && value === null ? VERDICT_PENDING : String(value);
  const rows = Object.entries(summary).filter(([key]) => key !== 'checks' && !meaningless(key)).map(([key, value]) =>
    el('tr', { class: key === 'verdict' && value ? 'status ' + value : '', 'data-key': key }, el('th', {}, key),
      el('td', {}, text(key, value)), el('td', { class: 'unit' }, unitOf(key))));
  for (const c of summary.checks || [])
    rows.push(el('tr', { class: c.passed ? '' : 'status suspect' }, el('th', {}, 'check ' + c.name),
      el('td', {}, number(c.value) + (c.passed ? ' ≤ ' : ' > ') + number(c.bound)), el('td', { class: 'unit' }, c.passed ? 'passed' : 'FAILED')));
  if (note) rows.unshift(el('tr', {}, el('th', { colspan: 3 }, 'summary ' + note)));
  document.getElementById('job-summary').replaceChildren(...rows);
}

function downloadLink(text, href, id) {
  const link = el('a', { href, id, download: '' }, text);
  link.addEventListener('click', async (event) => {     // with a token, a link alone would be refused
    if (!sessionStorage.getItem('stoss-token')) return;
    event.preventDefault();
    const blob = await (await api(href)).blob();
    const save = el('a', { href: URL.createObjectURL(blob), download: href.split('/').pop() });
    save.click();
  });
  return link;
}

function showDownloads(job) {
  const links = [];
  const add = (text, href, id) => links.push(downloadLink(text, href, id), ' ');
  if (job.links.result) add('result.h5', job.links.result, 'download-result');
  if (job.links.result_xdmf) add('result.xdmf', job.links.result_xdmf, 'download-xdmf');
  if (job.kind === 'simulation' && job.status !== 'queued') {
    add('series.csv', `/v1/jobs/${job.id}/series?format=csv`, 'download-series-csv');
    add('series.json', `/v1/jobs/${job.id}/series`, 'download-series-json');
  }
  if (job.links.study) {
    add('study.csv', job.links.study + '?format=csv', 'download-study-csv');
    add('study.md', job.links.study + '?format=markdown', 'download-study-md');
  }
  add('scene.json', job.links.scene, 'download-scene');
  add('log.txt', job.links.log, 'download-log');
  document.getElementById('job-downloads').replaceChildren('Downloads: ', ...links);
}

function showJobHeader(job) {
  document.getElementById('job-panel').hidden = false;
  document.getElementById('job-title').textContent = job.name || job.id;
  document.getElementById('job-kind').textContent = `${job.kind} ${job.id} · attempt ${job.attempt}`;
  const status = document.getElementById('job-status');
  const reasons = suspectReasons(job.summary);  // a suspect run succeeded but is shown amber with its reasons
  status.textContent = job.status + (reasons ? ' · suspect' : '');
  status.className = 'status ' + job.status + (reasons ? ' suspect' : '');
  const eta = job.progress.eta_seconds;
  document.getElementById('job-progress').textContent = progressText(job, true) + (eta !== null ? ' · ETA ' + duration(eta) : '');
  document.getElementById('cancel-button').hidden = !job.links.cancel;
  document.getElementById('job-error').textContent = job.error || reasons;
  showBeforeRun(document.getElementById('job-warnings'), { warnings: job.warnings });
  showDownloads(job);
  if (job.summary) showSummary(job.summary, '');
}

document.getElementById('cancel-button').addEventListener('click', async () => {
  await api(`/v1/jobs/${shown.id}/cancel`, { method: 'POST' });
  refreshList();
});

// A study: error against wall seconds, one line per scheme, log–log; and the table.
async function showStudy(job) {
  const view = document.getElementById('study-view');
  view.hidden = job.kind !== 'study';
  if (job.kind !== 'study' || job.status !== 'succeeded' || shown.studyShown) return;
  const { body } = await apiJson(job.links.study);
  shown.studyShown = true;
  // A line per scheme at fixed steps, and one per scheme with steps chosen by a tolerance ("adaptive …").
  const lineOf = (r) => (r.tolerance > 0 ? 'adaptive ' + r.scheme : r.scheme);
  const labelOf = (r) => (r.tolerance > 0 ? 'TOL=' + r.tolerance : 'h=' + r.step);
  const lines = [...new Set(body.rows.map(lineOf))];
  const plotted = body.rows.filter((r) => r.completed && r.displacement_error > 0);
  const points = plotted
    .map((r) => { const row = [r.wall_seconds, ...lines.map(() => null)]; row[1 + lines.indexOf(lineOf(r))] = r.displacement_error; return row; })
    .sort((a, b) => a[0] - b[0]);
  const xs = points.map((p) => p[0]);
  const ys = plotted.map((r) => r.displacement_error);
  const timing = body.timing || 'wall seconds: one run';
  const box = document.getElementById('plot-accuracy');
  box.dataset.points = String(points.length);
  box.dataset.lines = String(lines.length);
  box.dataset.pointLabels = JSON.stringify(plotted.map(labelOf));
  const dashed = Object.fromEntries(lines.filter((l) => l.startsWith('adaptive ')).map((l) => [l, { strokePattern: [6, 3] }]));
  const graph = new Dygraph(box, points, { labels: ['wall seconds', ...lines], title: 'Displacement error at the end against wall time',
    xlabel: body.repeat > 1 ? `wall seconds (median of ${body.repeat} runs)` : 'wall seconds (one run)', ylabel: 'max nodal displacement error (' + UNITS + ')',
    logscale: true, connectSeparatedPoints: true, drawPoints: true, pointSize: 3, legend: 'always', height: 300, series: dashed,
    labelsDiv: document.getElementById('accuracy-legend'),
    axes: { x: { logscale: true, ticker: logTicks }, y: { axisLabelWidth: 64, ticker: logTicks } },
    dateWindow: [Math.min(...xs) / 1.5, Math.max(...xs) * 1.5], valueRange: [Math.min(...ys) / 1.5, Math.max(...ys) * 1.5] });
  // Each point says its step size, or its tolerance.
  graph.ready(() => graph.setAnnotations(plotted.map((r) => ({ series: lineOf(r), x: r.wall_seconds, shortText: labelOf(r),
    text: r.tolerance > 0 ? `${r.scheme}, time.tolerance = ${r.tolerance}, ${r.steps} steps` : `${r.scheme}, h = ${r.step}`,
    width: r.tolerance > 0 ? 76 : 48, height: 14, cssClass: 'step-label' }))));
  document.getElementById('study-timing').textContent = timing + ' of each scheme and step (wall time, not CPU time).';
  const columns = ['scheme', 'step', 'steps', 'displacement_error', 'energy_error', 'momentum_error', 'wall_seconds', 'newton_per_step'];
  if (body.rows.some((r) => r.tolerance > 0)) columns.splice(2, 0, 'tolerance');  // step is then the first step
  const unitOfColumn = { step: UNITS, tolerance: UNITS, displacement_error: UNITS, energy_error: 'relative', momentum_error: 'relative',
    wall_seconds: body.repeat > 1 ? `s, median (fastest–slowest) of ${body.repeat}` : 's' };
  const head = el('tr', {}, ...columns.map((c) => el('th', {}, c + (unitOfColumn[c] ? ` (${unitOfColumn[c]})` : ''))));
  // Wall seconds: the median, and the fastest and slowest of the point's runs when it ran more than once.
  const wallCell = (r) => {
    const runs = r.wall_seconds_runs || [];
    if (runs.length < 2) return el('td', {}, number(r.wall_seconds));
    const spread = `${number(Math.min(...runs))}–${number(Math.max(...runs))}`;
    return el('td', { class: 'wall', title: `${runs.length} runs: ${runs.map(number).join(', ')} s` },
      `${number(r.wall_seconds)} (${spread})`);
  };
  const rows = body.rows.map((r) => el('tr', { class: r.completed ? '' : 'failed' },
    ...columns.map((c) => (c === 'wall_seconds' && r.completed ? wallCell(r)
      : el('td', {}, r[c] === null || r[c] === undefined ? (r.failure || '') : number(r[c]))))));
  document.getElementById('study-table').replaceChildren(head, ...rows);
}

async function refreshLog(job) {
  const response = await api(job.links.log);
  const log = document.getElementById('job-log');
  log.textContent = await response.text();
}

async function pollJob(id) {
  if (shown.id !== id) return;
  const { status, body: job } = await apiJson('/v1/jobs/' + id);
  if (status !== 200) { document.getElementById('job-error').textContent = job.detail; return; }
  showJobHeader(job);
  const seriesDone = await pollSeries(job);
  await showStudy(job);
  await refreshLog(job);
  if (!FINAL.includes(job.status) || !seriesDone) shown.timer = setTimeout(() => pollJob(id).catch(report), POLL_MS);
}

function showJob(id) {
  clearTimeout(shown.timer);
  shown = { id, attempt: null, studyShown: false };
  resetPlots(shown);
  document.getElementById('job-summary').replaceChildren();
  document.getElementById('study-table').replaceChildren();
  document.getElementById('plot-accuracy').replaceChildren();
  document.querySelectorAll('#jobs tr').forEach((row) => row.classList.toggle('selected', row.dataset.id === id));
  history.replaceState(null, '', '#job=' + id);
  pollJob(id).catch(report);
}

// ---- start ------------------------------------------------------------------------------------------------

function report(error) {
  if (error instanceof Unauthorized) return;
  document.getElementById('connection').textContent = 'error: ' + error.message;
}

let listTimer = null;
async function pollList() {
  clearTimeout(listTimer);
  try {
    await refreshList();
    document.getElementById('connection').textContent = '';
  } catch (error) {
    report(error);
    if (error instanceof Unauthorized) return;
  }
  listTimer = setTimeout(pollList, LIST_POLL_MS);
}

async function start() {
  try {
    await loadExamples();
  } catch (error) {
    report(error);
    return;
  }
  pollList();
  const match = location.hash.match(/job=([0-9a-f]{32})/);
  if (match) showJob(match[1]);
}

start();
