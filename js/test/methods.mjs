// The JS module's point maps: each method and the widths of its arguments, every one a
// Float32Array of points of that many floats (shared by the argument tables of api.test.mjs
// and hostile.test.mjs, which make the arrays their own way).
export const POINT_MAPS = {
  diskPolar: [2],
  diskPolarInverse: [2],
  diskConcentric: [2],
  diskConcentricInverse: [2],
  diskPolar4Inverse: [2],
  diskConcentric4Inverse: [2],
  triangleUniform: [2],
  triangleUniformInverse: [3],
  triangleSqrtMap: [2],
  triangleSqrtMapInverse: [3],
  sphereEqualArea: [2],
  sphereEqualAreaInverse: [3],
  sphereEqualAreaWrap: [2],
  sphereEquirect: [2],
  sphereEquirectInverse: [3],
  sphereUniform: [2],
  sphereUniformInverse: [3],
  sphereUniformHemisphere: [2],
  sphereUniformHemisphereInverse: [3],
  sphereCosineHemisphere: [2],
  sphereCosineHemisphereInverse: [3],
  sphereEqualAreaPdfToSolidAngle: [1],
  sphereCosineHemispherePdf: [1],
  sphereEquirectPdfToSolidAngle: [1, 3],
  microfacetGgxD: [5],
  microfacetGgxG1: [5],
  microfacetGgxG2: [8],
  microfacetGgxVisibleNormal: [7],
  microfacetGgxVisibleNormalPdf: [8],
  microfacetGgxReflect: [7],
  microfacetGgxReflectPdf: [8],
  microfacetGgxReflectBounded: [7],
  microfacetGgxReflectBoundedPdf: [8],
  envmapLuminance: [3],
  envmapEquirectPdfToSolidAngle: [1, 1],
};

/** `POINT_MAPS` with each width made an argument spec by `arg(width)`. */
export const pointMaps = (arg) => Object.fromEntries(Object.entries(POINT_MAPS).map(([name, widths]) => [name, widths.map(arg)]));
