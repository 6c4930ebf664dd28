"""Open Inventor and VRML text read into a scene graph of nodes (their fields' raw values), for
:mod:`drake_grasp.objects.inventor_mesh` to turn into triangles.

Why: GraspIt!'s objects (graspit-simulator/graspit, ``models/objects``) are Open Inventor ASCII files
(``#Inventor V2.0 ascii``, ``V2.1``) and VRML 2.0 files (``#VRML V2.0 utf8``, some of them named
``.IV``), which Coin reads for GraspIt and which neither trimesh nor Drake reads. Both are one syntax:
a node is ``[DEF name] Type { field value ... child nodes ... }``, a value is numbers, a word, a
quoted string, a node, ``USE name`` or a ``[ ... ]`` list of those; ``#`` starts a comment outside
strings and commas are whitespace. VRML 1.0 (``#VRML V1.0 ascii``) is Inventor's syntax too.

The parser knows no node's schema: it reads every node's fields generically (after a field name,
the numbers that follow, else one word, string, node or bracketed list), so a node it does not know
is read, kept and later skipped, its braces matched. VRML's ``PROTO``, ``EXTERNPROTO`` and
``ROUTE`` statements are skipped. Inventor's field connections (``= Engine {...} . output``) are
skipped. A file whose braces or brackets do not close, or that ``USE``s a name it never ``DEF``ined,
is an ObjectError naming the line (one line).
"""

from __future__ import annotations

import dataclasses
import re

from drake_grasp.objects.spec import ObjectError

# A quoted string (escaped quotes kept), a comment, a bracket or brace, or a run of other characters
# (words and numbers). Commas and whitespace separate tokens and are dropped.
_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"?|#[^\n\r]*|[{}\[\]()|]|[^\s,{}\[\]()|"#]+')
_PUNCTUATION = frozenset("{}[]()|")
_STATEMENTS = frozenset(("PROTO", "EXTERNPROTO", "ROUTE"))


@dataclasses.dataclass(eq=False)
class Node:
    """One node of the scene: its type name, its fields (name → list of raw tokens and nodes, in
    the file's order; a single value and a ``[ ]`` list alike), its inline children (Inventor's
    group nodes) and the line it starts on (for messages)."""

    type: str
    fields: dict
    children: list
    line: int

    def nodes(self, field: str) -> list:
        """The nodes a field holds (VRML's ``children``, ``geometry``, ``coord``): [] if none."""
        return [item for item in self.fields.get(field, ()) if isinstance(item, Node)]

    def word(self, field: str, default: str) -> str:
        """A field's one word (an enum or boolean value, unquoted), or `default`."""
        values = self.fields.get(field)
        if not values or isinstance(values[0], Node):
            return default
        return str(values[0]).strip('"')


def is_number(token) -> bool:
    """Whether a token is where a number stands (it starts as one: a sign, a digit or a point)."""
    return isinstance(token, str) and token[:1] in "+-.0123456789" and token != "."


class _Parser:
    """Recursive descent over the tokens of one file."""

    def __init__(self, text: str, label: str):
        self.text, self.label = text, label
        self.tokens, self.starts = [], []
        for match in _TOKEN.finditer(text):
            token = match.group()
            if token[0] == "#":
                continue
            if token[0] == '"' and (len(token) < 2 or token[-1] != '"' or _escaped(token)):
                self.fail(match.start(), "a quoted string is never closed")
            self.tokens.append(token)
            self.starts.append(match.start())
        self.at = 0
        self.names: dict[str, Node] = {}

    def line(self, index: int | None = None) -> int:
        index = self.at if index is None else index
        position = self.starts[index] if index < len(self.starts) else len(self.text)
        return self.text.count("\n", 0, position) + 1

    def fail(self, position: int, problem: str):
        line = self.text.count("\n", 0, position) + 1
        raise ObjectError(f"{self.label}: line {line}: {problem}")

    def fail_here(self, problem: str, index: int | None = None):
        index = self.at if index is None else index
        self.fail(self.starts[index] if index < len(self.starts) else len(self.text), problem)

    def peek(self, ahead: int = 0) -> str | None:
        index = self.at + ahead
        return self.tokens[index] if index < len(self.tokens) else None

    def take(self) -> str:
        token = self.peek()
        if token is None:
            self.fail_here("the file ends inside a node (a '{' or '[' is never closed)")
        self.at += 1
        return token

    def starts_node(self) -> bool:
        token = self.peek()
        if token in ("DEF", "USE"):
            return True
        return token is not None and token not in _PUNCTUATION and token[0] != '"' and self.peek(1) == "{"

    def scene(self) -> list[Node]:
        """The top-level nodes (a stray closing brace at the top level, which Coin tolerates, is
        skipped)."""
        nodes = []
        while self.peek() is not None:
            token = self.peek()
            if token in _STATEMENTS:
                self.skip_statement()
            elif self.starts_node():
                nodes.append(self.node())
            elif token in ("}", "]"):
                self.at += 1
            else:
                self.fail_here(f"{token[:40]!r} where a node should start")
        return nodes

    def node(self) -> Node:
        token = self.take()
        if token == "USE":
            name = self.take()
            if name not in self.names:
                self.fail_here(f"USE {name[:40]!r}: no node was DEF'd by that name before", self.at - 1)
            return self.names[name]
        name = None
        if token == "DEF":
            name = self.take()
            token = self.take()
        line = self.line(self.at - 1)
        if self.peek() != "{":
            self.fail_here(f"expected '{{' after {token[:40]!r}")
        self.at += 1
        node = Node(token, {}, [], line)
        self.body(node)
        if name is not None:
            self.names[name] = node
        return node

    def body(self, node: Node) -> None:
        while True:
            token = self.peek()
            if token is None:
                self.fail(len(self.text), f"the file ends inside {node.type} (line {node.line}): its '{{' is never "
                          "closed")
            if token == "}":
                self.at += 1
                return
            if token in _STATEMENTS:
                self.skip_statement()
            elif self.starts_node():
                node.children.append(self.node())
            elif token in _PUNCTUATION or token[0] == '"' or is_number(token):
                self.at += 1  # not a field name: skipped (an unknown node's odd syntax)
            else:
                self.at += 1
                node.fields[token] = self.value()
                self.skip_connection()

    def value(self) -> list:
        token = self.peek()
        if token == "[":
            return self.items()
        if token == "NULL":
            self.at += 1
            return []
        if self.starts_node():
            return [self.node()]
        if is_number(token):
            start = self.at
            while is_number(self.peek()):
                self.at += 1
            return self.tokens[start:self.at]
        if token == "(":  # a bit mask: (SIDES | TOP)
            words = []
            while self.take() != ")":
                if self.peek() not in ("|", ")"):
                    words.append(self.peek())
            return words
        if token is None or token in "}]":
            return []
        self.at += 1
        return [token]

    def items(self) -> list:
        """The items of a ``[ ... ]`` list, the brackets consumed."""
        self.at += 1
        items = []
        while True:
            token = self.peek()
            if token == "]":
                self.at += 1
                return items
            if token is None:
                self.fail(len(self.text), "the file ends inside a '[ ... ]' list: its '[' is never closed")
            if token in _STATEMENTS:
                self.skip_statement()
            elif self.starts_node():
                items.append(self.node())
            elif token in ("{", "}", "["):
                self.fail_here(f"{token!r} inside a '[ ... ]' list")
            else:
                items.append(token)
                self.at += 1

    def skip_connection(self) -> None:
        """Inventor's ``= Engine {...} . output`` (a field connected to an engine): skipped."""
        if self.peek() != "=":
            return
        self.at += 1
        if self.starts_node():
            self.node()
        else:
            self.at += 1
        if self.peek() is not None and self.peek().startswith("."):
            self.at += 2 if self.peek() == "." else 1

    def skip_statement(self) -> None:
        """VRML's ``ROUTE a.b TO c.d``, ``PROTO name [...] {...}``, ``EXTERNPROTO name [...] url``."""
        keyword = self.take()
        if keyword == "ROUTE":
            self.at += 3
            return
        self.take()  # the prototype's name
        if self.peek() == "[":
            self.skip_group("[", "]")
        if keyword == "PROTO" and self.peek() == "{":
            self.skip_group("{", "}")
        elif keyword == "EXTERNPROTO":
            if self.peek() == "[":
                self.skip_group("[", "]")
            else:
                self.at += 1

    def skip_group(self, opening: str, closing: str) -> None:
        depth = 0
        while True:
            token = self.take()
            depth += (token == opening) - (token == closing)
            if depth == 0:
                return


def _escaped(token: str) -> bool:
    """Whether a string token's last quote is escaped (then the string is not closed)."""
    backslashes = len(token) - 1 - len(token[:-1].rstrip("\\"))
    return backslashes % 2 == 1


def parse_scene(text: str, label: str) -> list[Node]:
    """The top-level nodes of an Open Inventor or VRML text (its header line a comment).
    ObjectError (one line, naming `label` and the line) for a string, a brace or a bracket that is
    never closed, or a USE of a name never DEF'd."""
    return _Parser(text, label).scene()
