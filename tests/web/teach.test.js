/* The teaching page (zscan teach), as a learner uses it: opened from disk
 * with the network refused, in Debian's headless Chromium driven through
 * the DevTools protocol (playwright-core).  Every table read from the DOM
 * is compared with `zscan trace --format json` for the same polygons.
 *
 *   node tests/web/teach.test.js ZSCAN SOURCE_DIR WORK_DIR
 */
"use strict";
const assert = require("assert");
const fs = require("fs");
const path = require("path");
const { execFileSync, spawnSync } = require("child_process");
const { chromium } = require("playwright-core");

const [zscan, src, work] = process.argv.slice(2);
if (!zscan || !src || !work) {
  console.error("usage: node teach.test.js ZSCAN SOURCE_DIR WORK_DIR");
  process.exit(2);
}
fs.mkdirSync(work, { recursive: true });
const PAGE_LIMIT = 512 * 1024; /* docs/TEACHING.md: the page, engine included */

let failed = 0, n = 0;
async function check(name, fn) {
  n++;
  try { await fn(); console.log("ok " + n + " - " + name); }
  catch (e) { failed++; console.log("not ok " + n + " - " + name + "\n  " + String(e.stack || e).replace(/\n/g, "\n  ")); }
}

/* ---- the native side ---- */
function objOf(lesson) {
  let s = "", first = 1;
  lesson.polygons.forEach((p, i) => {
    s += "o polygon_" + i + "\n";
    for (const v of p.vertices) s += "v " + v.slice(0, 3).join(" ") + (v.length > 3 ? " " + [v[3] / 255, v[3] / 255, v[3] / 255].join(" ") : "") + "\n";
    s += "f " + p.vertices.map((_, j) => first + j).join(" ") + "\n";
    first += p.vertices.length;
  });
  return s;
}
function viewArgs(lesson) {
  const a = ["--ortho", "-0.5," + (lesson.width - 0.5) + ",-0.5," + (lesson.height - 0.5), "--eye", "0,0,0", "--target", "0,0,-1", "--near", "-10", "--far", "5", "--size", lesson.width + "x" + lesson.height];
  return lesson.algo === "zbuffer" ? a.concat(["--algo", "zbuffer"]) : a;
}
function nativeTrace(lesson, file) {
  const obj = path.join(work, file || "lesson.obj");
  fs.writeFileSync(obj, objOf(lesson));
  const out = execFileSync(zscan, ["trace", obj].concat(viewArgs(lesson), ["--format", "json"]), { encoding: "utf8" });
  return out.trim().split("\n").map(l => JSON.parse(l));
}
/* The page's way of showing a number (its num()). */
const num = v => v === null || v === undefined ? "far" : (Math.abs(v) < 1e-12 ? "0" : Number(v.toPrecision(6)).toString());

/* ---- the page's side ---- */
const cells = (page, sel) => page.$$eval(sel + " tr", trs => trs.slice(1).map(tr => Array.from(tr.children).map(c => c.textContent)));
const where = page => page.textContent("#where");
async function lessonOf(page) { /* the lesson the page holds, from its URL */
  const h = new URL(page.url()).hash.replace(/^#/, "");
  const q = Object.fromEntries(h.split("&").map(p => p.split("=")));
  return JSON.parse(Buffer.from(q.lesson.replace(/-/g, "+").replace(/_/g, "/"), "base64").toString("utf8"));
}
async function stepTo(page, k) { await page.click("#first"); for (let i = 0; i < k; i++) await page.click("#next"); }
async function setField(page, p, v, k, value) {
  const inp = page.locator("input[data-path=\"polygons[" + p + "].vertices[" + v + "]\"][data-k=\"" + k + "\"]");
  await inp.fill(String(value));
  await inp.dispatchEvent("change");
}
const msg = (page, p) => page.textContent(".msg[data-path=\"" + p + "\"]");

(async () => {
  const html = path.join(work, "teach.html");
  execFileSync(zscan, ["teach", "-o", html]);
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || "/usr/bin/chromium", args: ["--no-sandbox", "--disable-gpu"] });
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 }, offline: true });
  const outside = [];
  await context.route("**/*", r => { const u = r.request().url(); if (u.startsWith("file:") || u.startsWith("data:")) r.continue(); else { outside.push(u); r.abort(); } });
  const console_ = [];
  const watch = page => {
    page.on("console", m => { if (m.type() === "error" || m.type() === "warning") console_.push(m.type() + ": " + m.text()); });
    page.on("pageerror", e => console_.push("page error: " + e.message));
    return page;
  };
  const page = watch(await context.newPage());
  await page.goto("file://" + html);
  await page.waitForSelector("body[data-ready='1']");

  await check("the page, engine inlined, stays under its documented size", async () => {
    assert.ok(fs.statSync(html).size <= PAGE_LIMIT, fs.statSync(html).size + " bytes");
  });

  await check("the lecture's scanline example: the module's pixels and counters equal the native build's", async () => {
    const lines = execFileSync(zscan, ["trace", path.join(src, "tests/data/lecture/two_polygons.obj")].concat(viewArgs({ width: 12, height: 10 }), ["--format", "json"]), { encoding: "utf8" }).trim().split("\n");
    const f = JSON.parse(lines[lines.length - 1]).frame;
    const text = await page.textContent("#frame");
    assert.ok(text.includes("image hash " + f.image_hash), text + " / " + f.image_hash);
    assert.ok(text.includes("spans " + f.spans + ", pixels tested " + f.pixels_tested + ", written " + f.pixels_written), text);
    const stats = execFileSync(zscan, ["render", path.join(src, "tests/data/lecture/two_polygons.obj")].concat(viewArgs({ width: 12, height: 10 }), ["--algo", "scanline", "--shade", "id", "--stats", "-o", path.join(work, "ids.png")]), { encoding: "utf8" });
    assert.ok(stats.includes("\"image_hash\":\"" + f.image_hash + "\""), stats);
    console.log("# module and native: image hash " + f.image_hash + ", pixels written " + f.pixels_written);
  });

  await check("grid and tables together on one screen at 1280 x 800 (the lecture's scanline y = 6)", async () => {
    await stepTo(page, 3);
    for (const sel of ["#grid", "#polytable", "#edgetable", "#apt", "#aet", "#spans", "#rowbuf"]) {
      const b = await page.locator(sel).boundingBox();
      assert.ok(b && b.y + b.height <= 800 && b.x + b.width <= 1280, sel + " " + JSON.stringify(b));
    }
    await page.screenshot({ path: path.join(work, "teach-page.png") });
  });

  await check("drag a vertex: the lesson follows, to the nearest half unit", async () => {
    const h = page.locator("circle.handle[data-poly='0'][data-vert='2']"); /* (7, 3) */
    const b = await h.boundingBox(), cx = b.x + b.width / 2, cy = b.y + b.height / 2;
    const s = await page.$eval("#grid rect.px", r => Number(r.getAttribute("width")));
    await page.mouse.move(cx, cy); await page.mouse.down();
    await page.mouse.move(cx + s / 2, cy, { steps: 3 }); await page.mouse.move(cx + s, cy + 0.2 * s, { steps: 3 });
    await page.mouse.up();
    assert.strictEqual(await page.inputValue("input[data-path='polygons[0].vertices[2]'][data-k='0']"), "8");
    assert.strictEqual(await page.inputValue("input[data-path='polygons[0].vertices[2]'][data-k='1']"), "3");
    assert.deepStrictEqual((await lessonOf(page)).polygons[0].vertices[2], [8, 3, -2]);
  });

  await check("step to scanline 3: every table equals zscan trace --format json, fractions exactly", async () => {
    await stepTo(page, 3);
    assert.strictEqual(await where(page), "scanline 3 (4 of 10)");
    const lesson = await lessonOf(page), lines = nativeTrace(lesson);
    const head = lines[0], row = lines.find(l => l.y === 3);
    assert.deepStrictEqual(await cells(page, "#polytable"), head.polygon_table.map(p => [p.row, p.id, p.dy, num(p.z0), num(p.dzx), num(p.dzy)].map(String)));
    assert.deepStrictEqual(await cells(page, "#edgetable"), head.edge_table.map(e => [e.row, e.id, e.side, num(e.x), e.dx_fraction, e.dy].map(String)));
    assert.deepStrictEqual(await cells(page, "#apt"), row.active_polygons.map(p => [String(p.id), String(p.dy)]));
    const aet = await cells(page, "#aet");
    assert.deepStrictEqual(aet, row.active_edges.map(p => [p.xl_fraction, p.dxl_fraction, p.dyl, p.xr_fraction, p.dxr_fraction, p.dyr, num(p.zl), num(p.dzx), num(p.dzy), p.id].map(String)));
    assert.deepStrictEqual(await cells(page, "#spans"), row.spans.map(s => [s.x0, s.x1, s.id].map(String)));
    const rb = await cells(page, "#rowbuf");
    assert.deepStrictEqual(rb[0].slice(1), row.z.map(v => v === null ? "far" : num(v)));
    assert.deepStrictEqual(rb[2].slice(1), row.ids.map(v => v === null ? "-" : String(v)));
    console.log("# scanline 3 after the drag: " + aet.map(r => "xl " + r[0] + " xr " + r[3]).join(", "));
  });

  await check("step by pixel: the column marked, the row buffer filled up to it", async () => {
    await page.selectOption("#unit", "pixel");
    await page.click("#next"); await page.click("#next");
    assert.strictEqual(await where(page), "scanline 3 (4 of 10), column 2");
    const rb = await cells(page, "#rowbuf");
    assert.deepStrictEqual(rb[2].slice(1, 5), ["-", "-", "-", ""]);
    assert.strictEqual(await page.$eval("#rowbuf tr:nth-child(2) td.now", td => td.cellIndex), 3);
    await page.selectOption("#unit", "row");
  });

  await check("the exercise: the next active edge table answered wrong, then right", async () => {
    await page.check("#exercise");
    await stepTo(page, 4);
    const lesson = await lessonOf(page), row = nativeTrace(lesson).find(l => l.y === 4);
    assert.ok(await page.locator("#aet").isHidden(), "the table is hidden until answered");
    const fill = async wrong => {
      for (let i = 0; i < row.active_edges.length; i++)
        for (const f of ["xl", "dxl", "xr", "dxr"])
          await page.fill(".ex-input[data-pair='" + i + "'][data-field='" + f + "']", wrong && i === 1 && f === "xl" ? "7" : row.active_edges[i][f + "_fraction"]);
      await page.click("#ex-check");
    };
    await fill(true);
    const total = 4 * row.active_edges.length;
    assert.strictEqual(await page.textContent("#ex-result"), (total - 1) + " of " + total + " right: the red ones are not the engine's");
    assert.strictEqual(await page.getAttribute(".ex-input[data-pair='1'][data-field='xl'] >> xpath=..", "class"), "wrong");
    assert.strictEqual(await page.getAttribute(".ex-input[data-pair='0'][data-field='xl'] >> xpath=..", "class"), "right");
    assert.ok(await page.locator("#aet").isHidden());
    await fill(false);
    assert.strictEqual(await page.textContent("#ex-result"), "all " + total + " right");
    assert.ok(await page.locator("#aet").isVisible());
    /* the same fraction written otherwise is the same answer */
    const xl = row.active_edges[1].xl_fraction;
    if (xl.includes("/")) {
      const [a, b] = xl.split("/").map(Number);
      await page.fill(".ex-input[data-pair='1'][data-field='xl']", (2 * a) + "/" + (2 * b));
      await page.click("#ex-check");
      assert.strictEqual(await page.textContent("#ex-result"), "all " + total + " right");
    }
  });

  await check("the URL holds the lesson, the step and the exercise: a second page opens on the same state", async () => {
    const url = page.url();
    const again = watch(await context.newPage());
    await again.goto(url);
    await again.waitForSelector("body[data-ready='1']");
    assert.strictEqual(await where(again), await where(page));
    assert.strictEqual(await again.inputValue("input[data-path='polygons[0].vertices[2]'][data-k='0']"), "8");
    assert.ok(await again.isChecked("#exercise"));
    assert.deepStrictEqual(await cells(again, "#rowbuf"), await cells(page, "#rowbuf"));
    await again.close();
    await page.uncheck("#exercise");
  });

  await check("the z-buffer: the lecture's second example, its grids equal the native trace's", async () => {
    await page.selectOption("#preset", "square-and-slope");
    await stepTo(page, 1);
    assert.strictEqual(await where(page), "after polygon 1 (step 2 of 2)");
    const lesson = await lessonOf(page), lines = nativeTrace(lesson, "zbuffer.obj");
    const step = lines.find(l => l.step === 2), W = lesson.width;
    const ids = (await cells(page, "#idgrid")).map(r => r.slice(1));
    const want = [];
    for (let y = 0; y < lesson.height; y++) want.push(step.ids.slice(y * W, (y + 1) * W).map(v => v === null ? "-" : String(v)));
    assert.deepStrictEqual(ids, want);
    const z = (await cells(page, "#zgrid")).map(r => r.slice(1));
    assert.deepStrictEqual(z[2].slice(2, 7), ["2", "1", "0", "-1", "-2"]); /* the lecture's slope */
    assert.deepStrictEqual(z.map(r => r.join(" ")), step.z_view.reduce((a, v, k) => { const y = Math.floor(k / W); (a[y] = a[y] || []).push(Math.abs(v) < 1e-6 ? "0" : num(v)); return a; }, []).map(r => r.join(" ")));
    const f = lines[lines.length - 1].frame;
    assert.ok((await page.textContent("#frame")).includes("image hash " + f.image_hash));
    const stats = execFileSync(zscan, ["render", path.join(src, "tests/data/lecture/zbuffer_two.obj")].concat(viewArgs(lesson), ["--shade", "id", "--stats", "-o", path.join(work, "zb.png")]), { encoding: "utf8" });
    assert.ok(stats.includes("\"image_hash\":\"" + f.image_hash + "\""), stats);
    console.log("# z-buffer example, module and native: image hash " + f.image_hash);
    /* by pixel: the slope's cells one at a time, over the square's buffers */
    await page.selectOption("#unit", "pixel");
    const before = lines.find(l => l.step === 1), cellsWritten = [];
    for (let k = 0; k < step.ids.length; k++) if (step.ids[k] !== before.ids[k]) cellsWritten.push(k);
    assert.strictEqual(await where(page), "after polygon 1 (step 2 of 2), cell 1 of " + cellsWritten.length);
    const first = before.ids.map(v => v === null ? "-" : String(v));
    first[cellsWritten[0]] = String(step.ids[cellsWritten[0]]);
    assert.deepStrictEqual((await cells(page, "#idgrid")).map(r => r.slice(1)).flat(), first);
    assert.deepStrictEqual(await page.$$eval("#idgrid td.now", tds => tds.map(td => [td.parentNode.rowIndex - 1, td.cellIndex - 1])),
                           [[Math.floor(cellsWritten[0] / W), cellsWritten[0] % W]]);
    await page.selectOption("#unit", "row");
  });

  await check("bad input is a message beside its field, the page still drawn", async () => {
    await page.selectOption("#preset", "two-polygons");
    await setField(page, 0, 1, 0, 20);
    assert.strictEqual(await msg(page, "polygons[0].vertices[1]"), "x = 20 is off the grid: 0 to 11");
    await setField(page, 0, 1, 0, 7);
    assert.strictEqual(await msg(page, "polygons[0].vertices[1]"), "");
    await setField(page, 1, 2, 0, 4); await setField(page, 1, 2, 1, 5); /* (8,9) (6,7) (4,5): one line */
    assert.strictEqual(await msg(page, "polygons[1]"), "degenerate: its corners are on one line (no area)");
    await setField(page, 1, 2, 1, "abc");
    assert.strictEqual(await msg(page, "polygons[1].vertices[2]"), "expected numbers");
    await page.selectOption("#preset", "two-polygons");
    for (let i = 0; i < 6; i++) await page.click("button.add-vert[data-poly='0']");
    assert.strictEqual(await msg(page, "polygons[0]"), "9 vertices: at most 8");
    await page.fill("#width", "40"); await page.dispatchEvent("#width", "change");
    assert.strictEqual(await msg(page, "width"), "expected a whole number 2 to 32");
    assert.ok(await page.locator("#grid rect.px").count() > 0 && await page.locator("#tables table").count() > 0, "the page is not blank");
  });

  await check("zscan teach --lesson: the page opens on the lesson; a bad one is refused with the page's message", async () => {
    const lesson = { width: 10, height: 8, algo: "scanline", polygons: [{ vertices: [[1, 1, 0], [8, 2, 1], [4, 6, -1]] }] };
    const good = path.join(work, "lesson.json"), bad = path.join(work, "bad.json"), out = path.join(work, "lesson.html");
    fs.writeFileSync(good, JSON.stringify(lesson));
    execFileSync(zscan, ["teach", "-o", out, "--lesson", good]);
    const p = watch(await context.newPage());
    await p.goto("file://" + out);
    await p.waitForSelector("body[data-ready='1']");
    assert.deepStrictEqual(await lessonOf(p), lesson);
    await stepTo(p, 3);
    const row = nativeTrace(lesson, "given.obj").find(l => l.y === 3);
    assert.deepStrictEqual((await cells(p, "#aet")).map(r => r[0] + " " + r[3]), row.active_edges.map(e => e.xl_fraction + " " + e.xr_fraction));
    await p.close();
    lesson.polygons[0].vertices[1] = [8, 2];
    fs.writeFileSync(bad, JSON.stringify(lesson));
    const r = spawnSync(zscan, ["teach", "-o", path.join(work, "never.html"), "--lesson", bad], { encoding: "utf8" });
    assert.strictEqual(r.status, 1);
    assert.strictEqual(r.stderr, "zscan teach: " + bad + ": polygons[0].vertices[1]: expected [x, y, z] or [x, y, z, I]\n");
    assert.ok(!fs.existsSync(path.join(work, "never.html")));
  });

  await check("nothing asked of the network, nothing in the console", async () => {
    assert.deepStrictEqual(outside, []);
    assert.deepStrictEqual(console_, []);
  });

  await browser.close();
  console.log("1.." + n);
  process.exit(failed ? 1 : 0);
})().catch(e => { console.error(e); process.exit(1); });
