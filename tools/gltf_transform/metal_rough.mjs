// The peer of `shadelab convert gltf`: gltf-transform's metalRough() (KHR_materials_pbrSpecularGlossiness ->
// metallic-roughness + KHR_materials_specular + KHR_materials_ior), as the library ships it, on IN; writes OUT.
//   node tools/gltf_transform/metal_rough.mjs IN.gltf|glb OUT.gltf|glb
import { NodeIO } from '@gltf-transform/core';
import { KHRONOS_EXTENSIONS } from '@gltf-transform/extensions';
import { metalRough } from '@gltf-transform/functions';

const [input, output] = process.argv.slice(2);
if (!input || !output) {
  console.error('usage: node metal_rough.mjs IN OUT');
  process.exit(2);
}
const io = new NodeIO().registerExtensions(KHRONOS_EXTENSIONS);
const doc = await io.read(input);
await doc.transform(metalRough());
await io.write(output, doc);
