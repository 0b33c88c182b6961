from enum import StrEnum

class Convention(StrEnum):
    DH = "dh"
    HAYATI = "hayati"

    def __str__(self) -> str:
        return str(self.value)
