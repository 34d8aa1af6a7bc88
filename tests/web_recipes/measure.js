// What both recipe pages measure (run_web_recipes.py checks it): for every pixel the building covers, the
// irradiance the engine applied, pi * lit / albedo (a Lambert surface lit by irradiance E shows albedo / pi * E),
// against the lightmap's value at that pixel's TEXCOORD_1, decoded as docs/export.md says (byte / 255 * intensity,
// bilinear between texel centres, clamped at the edges) from the PNG's bytes, which the test read in Python.
export const SIZE = 256;

function sampleLightmap(lightmap, u, v, channel) {
  const x = Math.min(Math.max(u * lightmap.width - 0.5, 0), lightmap.width - 1);
  const y = Math.min(Math.max(v * lightmap.height - 0.5, 0), lightmap.height - 1);
  const x0 = Math.floor(x), y0 = Math.floor(y);
  const x1 = Math.min(x0 + 1, lightmap.width - 1), y1 = Math.min(y0 + 1, lightmap.height - 1);
  const at = (xi, yi) => lightmap.rgb[(yi * lightmap.width + xi) * 3 + channel];
  const top = at(x0, y0) * (x0 + 1 - x) + at(x1, y0) * (x - x0);
  const bottom = at(x0, y1) * (x0 + 1 - x) + at(x1, y1) * (x - x0);
  return (top * (y0 + 1 - y) + bottom * (y - y0)) / 255 * lightmap.intensity;
}

// lit, albedo, uv1: RGBA float frames of SIZE x SIZE, the same view; pixels the building does not cover have
// alpha 0 in the albedo frame.
export async function compareWithLightmap(lit, albedo, uv1) {
  const lightmap = await (await fetch('./lightmap.json')).json();
  const ratios = [];
  let covered = 0;
  for (let pixel = 0; pixel < SIZE * SIZE; ++pixel) {
    if (albedo[pixel * 4 + 3] < 0.5) continue;
    covered += 1;
    for (let channel = 0; channel < 3; ++channel) {
      const surface = albedo[pixel * 4 + channel];
      const expected = sampleLightmap(lightmap, uv1[pixel * 4], uv1[pixel * 4 + 1], channel);
      // Dark albedo or a dark texel says little: 8-bit quantisation alone is several per cent there.
      if (surface < 0.02 || expected < 0.15 * lightmap.intensity) continue;
      ratios.push(Math.PI * lit[pixel * 4 + channel] / surface / expected);
    }
  }
  ratios.sort((a, b) => a - b);
  const quantile = (q) => ratios.length ? ratios[Math.min(ratios.length - 1, Math.floor(q * ratios.length))] : null;
  return { covered_pixels: covered, compared_channels: ratios.length, intensity: lightmap.intensity,
           ratio_p10: quantile(0.1), ratio_median: quantile(0.5), ratio_p90: quantile(0.9) };
}

// The result goes to the page (for a person looking at it) and to the runner's server, which waits for it in real
// time: a DOM dump after a virtual-time budget raced the module's awaits (WebGL reads on SwiftShader) and came back
// empty now and then.
export function report(result) {
  const text = JSON.stringify(result);
  document.getElementById('result').textContent = 'RESULT ' + text;
  fetch('/result', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: text });
}
