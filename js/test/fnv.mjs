// FNV-1a 64 over 32-bit words (little-endian bytes), as registry/src/fingerprint.rs hashes:
// the JS tests' hasher, on two 32-bit halves.
export class Fnv {
  constructor() {
    this.hi = 0xcbf29ce4;
    this.lo = 0x84222325;
  }
  word(w) {
    for (let i = 0; i < 4; i++) {
      const lo = (this.lo ^ ((w >>> (8 * i)) & 0xff)) >>> 0;
      // (hi:lo) * 0x100000001b3 mod 2^64 = (hi:lo) * 0x1b3 + (lo << 40)
      const p = lo * 0x1b3;
      const carry = Math.floor(p / 2 ** 32);
      this.lo = p >>> 0;
      this.hi = (this.hi * 0x1b3 + carry + ((lo << 8) >>> 0)) >>> 0;
    }
  }
  words(a) {
    for (let i = 0; i < a.length; i++) this.word(a[i]);
  }
  floats(f) {
    this.words(new Uint32Array(f.buffer, f.byteOffset, f.length));
  }
  hex() {
    return this.hi.toString(16).padStart(8, '0') + this.lo.toString(16).padStart(8, '0');
  }
}
