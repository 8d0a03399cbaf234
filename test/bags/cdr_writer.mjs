// A CDR writer for the tests' ROS 2 messages, written from the OMG CDR rules (independent of
// conicloc's reader): plain little-endian CDR after the 4-byte encapsulation header, alignment
// counted from its end.
export class Cdr {
  constructor() {
    this.parts = [];
    this.size = 0;
  }
  bytes(array) {
    this.parts.push(array);
    this.size += array.length;
  }
  align(n) {
    const pad = (n - (this.size % n)) % n;
    if (pad) this.bytes(new Uint8Array(pad));
  }
  u8(value) {
    this.bytes(Uint8Array.of(value));
  }
  u32(value) {
    this.align(4);
    const b = new Uint8Array(4);
    new DataView(b.buffer).setUint32(0, value, true);
    this.bytes(b);
  }
  i32(value) {
    this.align(4);
    const b = new Uint8Array(4);
    new DataView(b.buffer).setInt32(0, value, true);
    this.bytes(b);
  }
  string(text) {
    const utf8 = new TextEncoder().encode(text);
    this.u32(utf8.length + 1);
    this.bytes(utf8);
    this.bytes(new Uint8Array(1));
  }
  message() {
    const out = new Uint8Array(4 + this.size);
    out.set([0x00, 0x01, 0x00, 0x00]);
    let at = 4;
    for (const part of this.parts) {
      out.set(part, at);
      at += part.length;
    }
    return out;
  }
}
