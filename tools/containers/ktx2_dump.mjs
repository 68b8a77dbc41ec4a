// Reads a KTX 2.0 file with ktx-parse (an independent reader, npm) and prints what a test checks as JSON:
// the header, the Data Format Descriptor, the key/value data, the level layout, violations of the KTX 2.0
// layout rules it checks itself, and the texels asked for, decoded here from the Vulkan format definitions.
//
//   node ktx2_dump.mjs FILE [LEVEL:FACE:X:Y ...]
import { readFileSync } from 'node:fs';
import { read } from 'ktx-parse';

const [file, ...queries] = process.argv.slice(2);
const bytes = new Uint8Array(readFileSync(file));
const ktx = read(bytes);

// Texel size and decoder per VkFormat (Vulkan 1.3 "Formats"; "Unsigned 11-bit / 10-bit floating-point";
// "Shared exponent").
function half(bits) {
  const s = bits >> 15, e = (bits >> 10) & 31, m = bits & 1023;
  const v = e === 0 ? m * 2 ** -24 : e === 31 ? (m ? NaN : Infinity) : (1 + m / 1024) * 2 ** (e - 15);
  return s ? -v : v;
}
function ufloat(bits, mbits) {
  const e = bits >> mbits, m = bits & ((1 << mbits) - 1);
  if (e === 31) return m ? NaN : Infinity;
  return e === 0 ? (m / 2 ** mbits) * 2 ** -14 : (1 + m / 2 ** mbits) * 2 ** (e - 15);
}
const formats = {
  83: { name: 'VK_FORMAT_R16G16_SFLOAT', size: 4, typeSize: 2,
        decode: (dv, o) => [0, 1].map((c) => half(dv.getUint16(o + 2 * c, true))) },
  97: { name: 'VK_FORMAT_R16G16B16A16_SFLOAT', size: 8, typeSize: 2,
        decode: (dv, o) => [0, 1, 2, 3].map((c) => half(dv.getUint16(o + 2 * c, true))) },
  109: { name: 'VK_FORMAT_R32G32B32A32_SFLOAT', size: 16, typeSize: 4,
         decode: (dv, o) => [0, 1, 2, 3].map((c) => dv.getFloat32(o + 4 * c, true)) },
  122: { name: 'VK_FORMAT_B10G11R11_UFLOAT_PACK32', size: 4, typeSize: 4,
         decode: (dv, o) => { const p = dv.getUint32(o, true);
           return [ufloat(p & 0x7ff, 6), ufloat((p >>> 11) & 0x7ff, 6), ufloat(p >>> 22, 5)]; } },
  123: { name: 'VK_FORMAT_E5B9G9R9_UFLOAT_PACK32', size: 4, typeSize: 4,
         decode: (dv, o) => { const p = dv.getUint32(o, true), s = 2 ** ((p >>> 27) - 24);
           return [(p & 511) * s, ((p >>> 9) & 511) * s, ((p >>> 18) & 511) * s]; } },
};

const problems = [];
const fmt = formats[ktx.vkFormat];
if (!fmt) problems.push(`vkFormat ${ktx.vkFormat} is not one of the formats this reader decodes`);
if (fmt && ktx.typeSize !== fmt.typeSize) problems.push(`typeSize ${ktx.typeSize}, expected ${fmt.typeSize}`);
if (ktx.supercompressionScheme !== 0) problems.push('supercompressed');
const dfd = ktx.dataFormatDescriptor[0];
if (fmt && dfd.bytesPlane[0] !== fmt.size) problems.push(`bytesPlane0 ${dfd.bytesPlane[0]}, expected ${fmt.size}`);
const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
// The index: dfdByteLength equals dfdTotalSize; the key/value data is sorted by key.
const dfdOffset = view.getUint32(48, true), dfdLength = view.getUint32(52, true);
if (view.getUint32(dfdOffset, true) !== dfdLength) problems.push('dfdTotalSize differs from dfdByteLength');
const keys = Object.keys(ktx.keyValue);
for (let i = 1; i < keys.length; i++) {
  if (Buffer.compare(Buffer.from(keys[i - 1]), Buffer.from(keys[i])) >= 0) problems.push(`key/value data not sorted at '${keys[i]}'`);
}
// Levels: level i is max(1, w >> i) x max(1, h >> i), faceCount faces (6 for a cube, 1 for a 2D texture),
// smallest level first, each at a multiple of lcm(size, 4).
const levelWidth = (i) => Math.max(1, ktx.pixelWidth >> i);
const levelHeight = (i) => Math.max(1, Math.max(1, ktx.pixelHeight) >> i);
const levels = ktx.levels.map((l, i) => ({ byteOffset: l.levelData.byteOffset - bytes.byteOffset,
                                          byteLength: l.levelData.byteLength, uncompressed: l.uncompressedByteLength }));
const align = fmt ? (fmt.size % 4 === 0 ? fmt.size : fmt.size * 4) : 4;
levels.forEach((l, i) => {
  const expected = ktx.faceCount * levelWidth(i) * levelHeight(i) * (fmt ? fmt.size : 0);
  if (fmt && l.byteLength !== expected) problems.push(`level ${i}: byteLength ${l.byteLength}, expected ${expected}`);
  if (l.byteOffset % align !== 0) problems.push(`level ${i}: byteOffset ${l.byteOffset} not a multiple of ${align}`);
  if (l.byteOffset + l.byteLength > bytes.byteLength) problems.push(`level ${i}: past the end of the file`);
  if (i > 0 && l.byteOffset >= levels[i - 1].byteOffset) problems.push(`level ${i} is stored after level ${i - 1}`);
});

const texels = queries.map((q) => {
  const [level, face, x, y] = q.split(':').map(Number);
  const w = levelWidth(level), h = levelHeight(level);
  const l = ktx.levels[level].levelData;
  const dv = new DataView(l.buffer, l.byteOffset, l.byteLength);
  const rgba = fmt.decode(dv, ((face * h + y) * w + x) * fmt.size);
  return { level, face, x, y, value: rgba.map((v) => (Number.isFinite(v) ? v : String(v))) };
});

const keyValue = {};
for (const [k, v] of Object.entries(ktx.keyValue)) {
  keyValue[k] = typeof v === 'string' ? v : Buffer.from(v).toString('utf8').replace(/\0$/, '');
}
console.log(JSON.stringify({
  reader: 'ktx-parse', vkFormat: ktx.vkFormat, vkFormatName: fmt ? fmt.name : null, typeSize: ktx.typeSize,
  pixelWidth: ktx.pixelWidth, pixelHeight: ktx.pixelHeight, pixelDepth: ktx.pixelDepth, layerCount: ktx.layerCount,
  faceCount: ktx.faceCount, levelCount: ktx.levelCount, supercompressionScheme: ktx.supercompressionScheme,
  dfd: { vendorId: dfd.vendorId, descriptorType: dfd.descriptorType, versionNumber: dfd.versionNumber,
         colorModel: dfd.colorModel, colorPrimaries: dfd.colorPrimaries, transferFunction: dfd.transferFunction,
         flags: dfd.flags, texelBlockDimension: dfd.texelBlockDimension, bytesPlane: dfd.bytesPlane,
         samples: dfd.samples },
  keyValue, levels, problems, texels,
}));
