// The playground's editor: CodeMirror 6 with the scene language's highlighting and indentation,
// and the compiler's diagnostics as underlines with their message on hover. Bundled by esbuild
// into target/web/editor.js (scripts/build_web.sh); playground.js imports `createEditor`.
import { EditorState } from "@codemirror/state";
import {
  EditorView, keymap, lineNumbers, highlightActiveLine, highlightActiveLineGutter, drawSelection,
} from "@codemirror/view";
import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import {
  StreamLanguage, HighlightStyle, syntaxHighlighting, indentOnInput, bracketMatching, indentUnit,
} from "@codemirror/language";
import { setDiagnostics, lintGutter } from "@codemirror/lint";
import { searchKeymap, highlightSelectionMatches } from "@codemirror/search";
import { tags } from "@lezer/highlight";

// The grammar's keywords (grammar/sdf.pest: `keyword`), and its tokens below.
const KEYWORDS = new Set(["let", "fn", "import", "param", "in", "at", "camera", "light", "trace",
  "material", "bound", "occlusion", "fog", "background"]);

/** The scene language's tokens for highlighting, and its indentation: one level per open brace. */
const sdf = StreamLanguage.define({
  name: "sdf",
  startState: () => ({ depth: 0, comment: false }),
  copyState: (s) => ({ ...s }),
  token(stream, state) {
    if (state.comment) {
      if (stream.skipTo("*/")) {
        stream.match("*/");
        state.comment = false;
      } else stream.skipToEnd();
      return "comment";
    }
    if (stream.eatSpace()) return null;
    if (stream.match("//")) {
      stream.skipToEnd();
      return "comment";
    }
    if (stream.match("/*")) {
      state.comment = true;
      return "comment";
    }
    if (stream.match(/^"[^"\n]*"?/)) return "string";
    if (stream.match(/^#[A-Za-z0-9]*/)) return "color";
    // A number and its unit (`30deg`, `1e-3`), as the grammar's `quantity`.
    if (stream.match(/^(\d+(\.(?!\.)\d*)?|\.\d+)([eE][+-]?\d+)?/)) {
      stream.match(/^[A-Za-z]+/);
      return "number";
    }
    if (stream.match(/^[A-Za-z_][A-Za-z0-9_]*/)) {
      const word = stream.current();
      if (KEYWORDS.has(word)) return "keyword";
      // A call (`sphere(1)`, `union {`): the catalog's shapes and operators, and functions.
      if (stream.match(/^\s*[({]/, false)) return "function";
      return "variable";
    }
    const c = stream.next();
    if (c === "{") state.depth += 1;
    if (c === "}") state.depth = Math.max(0, state.depth - 1);
    if (c === "@") {
      stream.match(/^[A-Za-z_]\w*/);
      return "annotation";
    }
    return "|>+-*/^:.,;=".includes(c) ? "operator" : null;
  },
  indent(state, textAfter, context) {
    const closing = /^\s*\}/.test(textAfter) ? 1 : 0;
    return Math.max(0, state.depth - closing) * context.unit;
  },
  languageData: { commentTokens: { line: "//", block: { open: "/*", close: "*/" } }, indentOnInput: /^\s*\}$/ },
  tokenTable: { color: tags.color, annotation: tags.meta, function: tags.function(tags.variableName) },
});

const style = HighlightStyle.define([
  { tag: tags.keyword, color: "#c792ea" },
  { tag: tags.comment, color: "#7a7f8a", fontStyle: "italic" },
  { tag: tags.number, color: "#f78c6c" },
  { tag: tags.string, color: "#c3e88d" },
  { tag: tags.color, color: "#ffcb6b" },
  { tag: tags.meta, color: "#89ddff" },
  { tag: tags.function(tags.variableName), color: "#82aaff" },
  { tag: tags.operator, color: "#89ddff" },
]);

const theme = EditorView.theme({
  "&": { height: "100%", backgroundColor: "#1b1b1b", color: "#e8e8e8", fontSize: "13px" },
  ".cm-content": { fontFamily: "ui-monospace, monospace", caretColor: "#fff" },
  ".cm-gutters": { backgroundColor: "#161616", color: "#666", border: "none" },
  ".cm-activeLine, .cm-activeLineGutter": { backgroundColor: "#232323" },
  "&.cm-focused .cm-selectionBackground, .cm-selectionBackground": { backgroundColor: "#2f3b54 !important" },
  ".cm-tooltip": { backgroundColor: "#222", color: "#eee", border: "1px solid #444" },
}, { dark: true });

/**
 * UTF-16 offset in `doc` of a 1-based line and a 1-based column counted in characters (as the
 * compiler's JSON diagnostics count them).
 */
function offset(doc, line, column) {
  if (line > doc.lines) return doc.length;
  const l = doc.line(Math.max(1, line));
  let at = 0;
  for (let chars = 1; chars < column && at < l.text.length; chars += 1) {
    at += l.text.codePointAt(at) > 0xffff ? 2 : 1;
  }
  return l.from + at;
}

/**
 * An editor in `parent` holding `text`; `changed(text)` after every edit. Returns `text()`,
 * `setText(t)` and `diagnose(list, file)`: the compiler's JSON diagnostics of `file` underlined
 * (the others are the page's to list).
 */
export function createEditor(parent, text, changed) {
  const view = new EditorView({
    parent,
    state: EditorState.create({
      doc: text,
      extensions: [
        lineNumbers(), highlightActiveLineGutter(), history(), drawSelection(), indentOnInput(),
        bracketMatching(), highlightActiveLine(), highlightSelectionMatches(), lintGutter(),
        indentUnit.of("  "), sdf, syntaxHighlighting(style), theme,
        keymap.of([...defaultKeymap, ...historyKeymap, ...searchKeymap, indentWithTab]),
        EditorView.updateListener.of((u) => u.docChanged && changed(u.state.doc.toString())),
      ],
    }),
  });
  return {
    view,
    text: () => view.state.doc.toString(),
    setText(t) {
      view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: t } });
    },
    diagnose(list, file) {
      const doc = view.state.doc;
      const marks = list.filter((d) => d.file === file).map((d) => {
        let from = offset(doc, d.span.line, d.span.column);
        let to = offset(doc, d.span.end_line, d.span.end_column);
        // An empty span (an end of file, a missing token) underlines the character it is at.
        if (to <= from) [from, to] = from < doc.length ? [from, from + 1] : [Math.max(0, from - 1), from];
        const label = d.label ? ` (${d.label})` : "";
        return { from, to, severity: d.severity, message: `${d.message}${label}`, source: "sdfc" };
      });
      view.dispatch(setDiagnostics(view.state, marks));
    },
  };
}
