// Test vectors for handlab's LZ-string decoder, made with the reference implementation:
//   npm install lz-string@1.5.0 && node make_vectors.js > vectors.json
const LZ = require('lz-string');
const plain = [
  '', 'a', 'ab', 'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa', 'hello, world', 'TOBEORNOTTOBEORTOBEORNOT',
  'café crème brûlée', '漢字かなカナ', 'emoji 😀🖐️ pair', '{"frames":[{"id":1,"hands":[]}],"metadata":{"formatVersion":1}}',
  Array.from({length: 2000}, (_, i) => String.fromCharCode(32 + (i * 7919) % 95)).join(''),
  Array.from({length: 300}, (_, i) => 'frame ' + i + ' [' + (i * 0.1).toFixed(3) + ', ' + (i % 17) + ']').join('\n'),
];
console.log(JSON.stringify(plain.map(p => ({plain: p, base64: LZ.compressToBase64(p)})), null, 1));
