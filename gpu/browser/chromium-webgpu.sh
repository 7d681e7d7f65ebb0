#!/bin/sh
# Chromium with WebGPU on its software adapter (SwiftShader), for webgpu.test.mjs: the shared
# launcher (js/tools/chromium.mjs) passes --disable-gpu, which turns WebGPU off, so this
# wrapper drops that flag and adds the WebGPU ones. $CHROMIUM picks the browser.
browser=${CHROMIUM_BIN:-/usr/bin/chromium}
for a in "$@"; do
  shift
  [ "$a" = "--disable-gpu" ] || set -- "$@" "$a"
done
exec "$browser" --enable-unsafe-webgpu --enable-unsafe-swiftshader --use-webgpu-adapter=swiftshader \
  --use-angle=swiftshader --enable-features=Vulkan "$@"
