const S = "/tmp/probe_regress/s/", O = "/tmp/probe_regress/r2/";
const m = core.loadObject(S + "coarse.om");
const n = core.objectInfo(m).vertices;
const modes = [0, 9, 10, 999, 1000];
modes.forEach((k, i) => { const ids = []; for (let v = i; v < n; v += 5) ids.push(v); multirescloth.setModes(m, ids, k); });
multirescloth.exportSurface(m, O + "modes.ply", {colorBy: "mode"});
print(JSON.stringify(core.objectInfo(m).verticesPerMode.length));
preview.render(m, O + "modes.png", {width: 600, height: 400, colorBy: "mode", wireframe: false});
try { multirescloth.setModes(m, [0], 1001); print("1001 accepted"); } catch (e) { print("1001", e.message); }
try { multirescloth.setModes(m, [0], -1); print("-1 accepted"); } catch (e) { print("-1", e.message); }
