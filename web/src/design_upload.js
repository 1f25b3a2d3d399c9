// A person's image for the flag's design, sent to the gateway (/flag/design) in parts that each
// fit a WebSocket message: the file checked here first (its kind and size), then cut into parts
// of kPartBytes, each base64 in JSON, sent in order, each after the last is answered. The last
// part's answer is the server's: the design shown, or why not.
//
//   File --check--> parts [offset, length] --base64--> { name, size, offset, data } ... --> answer

export const kPartBytes = 144 * 1024;            ///< bytes of a part: the gateway's most
export const kMaxFileBytes = 4 * 1024 * 1024;    ///< the server's limit on a design file
export const kImageTypes = ["image/png", "image/jpeg"];

/// "" if `file` ({ name, size, type }) may be sent as a design, else why not.
export function checkDesignFile(file) {
  if (!kImageTypes.includes(file.type) && !/\.(png|jpe?g)$/i.test(file.name))
    return `${file.name}: not a PNG or JPEG file`;
  if (file.size === 0) return `${file.name}: the file is empty`;
  if (file.size > kMaxFileBytes) return `${file.name}: ${file.size} bytes; allowed up to 4 MiB`;
  return "";
}

/// The parts of a file of `size` bytes: [{ offset, length }], in order.
export function partsOf(size, partBytes = kPartBytes) {
  const parts = [];
  for (let offset = 0; offset < size; offset += partBytes) parts.push({ offset, length: Math.min(partBytes, size - offset) });
  return parts;
}

/// RFC 4648 base64 of a Uint8Array.
export function base64Of(bytes) {
  let binary = "";
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

/// Sends `file` (a File or Blob with a name) through `call(service, request)`, reporting
/// progress(sent, total) after each part; resolves with the last answer, rejects on a refusal.
export async function uploadDesign(file, call, progress = () => {}) {
  const problem = checkDesignFile(file);
  if (problem) throw new Error(problem);
  const bytes = new Uint8Array(await file.arrayBuffer());
  let answer = null;
  for (const { offset, length } of partsOf(bytes.length)) {
    answer = await call("/flag/design", { name: file.name, size: bytes.length, offset, data: base64Of(bytes.subarray(offset, offset + length)) });
    if (!answer?.accepted) throw new Error(answer?.reason || "refused");
    progress(offset + length, bytes.length);
  }
  return answer;
}
