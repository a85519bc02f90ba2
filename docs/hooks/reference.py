"""MkDocs hook: adds the generated reference pages (coopdrive.docs_reference.pages) to the site as it is built,
so the command line, config keys and topics in the docs are always those of the code being documented."""

from mkdocs.structure.files import File

from coopdrive.docs_reference.pages import GENERATED_PAGES


def on_files(files, config):
    for path, generate in GENERATED_PAGES.items():
        files.append(File.generated(config, path, content=generate()))
    return files
